//! Helpers for the end-to-end tests: locate (building if needed) the real `gen` and `estimate`
//! binaries of this workspace, in the same profile as the running test, and run them.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Mutex;

static BUILD_LOCK: Mutex<()> = Mutex::new(());

/// The target directory of the running test binary (`target/<profile>`).
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.parent()
        .and_then(Path::parent)
        .expect("test binary lives in target/<profile>/deps")
        .to_path_buf()
}

/// Path of binary `name` from package `package`, built with `cargo build` first so the test
/// never runs a stale binary (a no-op when it is up to date).
pub fn binary(package: &str, name: &str) -> PathBuf {
    let _guard = BUILD_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let dir = profile_dir();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.args(["build", "--quiet", "-p", package, "--bin", name]);
    if dir.file_name().is_some_and(|n| n == "release") {
        cmd.arg("--release");
    }
    let status = cmd
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .status()
        .expect("cargo runs");
    assert!(status.success(), "cargo build of {name} failed");
    let path = dir.join(name);
    assert!(path.exists(), "{} was not built", path.display());
    path
}

/// The `gen` binary.
pub fn gen_bin() -> PathBuf {
    binary("physvid-generator", "gen")
}

/// Runs `bin` with `args` and returns its output.
pub fn run(bin: &Path, args: &[&str]) -> Output {
    Command::new(bin).args(args).output().expect("binary runs")
}

/// Stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The `estimate` binary.
pub fn estimate_bin() -> PathBuf {
    binary("physvid-estimator", "estimate")
}

/// The `reproduce` binary.
pub fn reproduce_bin() -> PathBuf {
    binary("physvid-estimator", "reproduce")
}

/// Generates a dataset with the real `gen` into `dir` and returns its path as text.
pub fn gen_dataset(dir: &Path, scenario: &str, extra: &[&str]) -> String {
    let out = dir.to_str().expect("UTF-8 temp path").to_string();
    let mut args = vec!["--scenario", scenario, "--out", &out, "--force"];
    args.extend_from_slice(extra);
    let o = run(&gen_bin(), &args);
    assert!(o.status.success(), "gen failed: {}", stderr(&o));
    out
}

/// Reads `report.json` from an estimate output directory.
pub fn read_report(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("report.json")).expect("report.json written");
    serde_json::from_str(&text).expect("report.json is JSON")
}

/// The estimate of parameter `name` in a report.
pub fn estimate_of(report: &serde_json::Value, name: &str) -> f64 {
    report["parameters"]
        .as_array()
        .expect("parameters array")
        .iter()
        .find(|p| p["name"] == name)
        .and_then(|p| p["estimate"].as_f64())
        .unwrap_or_else(|| panic!("no estimate for {name}"))
}

/// Runs `bin` with `args` and asserts the bad-input contract: exit code 2 and one line on
/// stderr that contains `needle`.
pub fn assert_one_line_error(bin: &Path, args: &[&str], needle: &str) {
    let o = run(bin, args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(
        err.trim().lines().count(),
        1,
        "{args:?}: not one line: {err}"
    );
    assert!(err.contains(needle), "{args:?}: {err}");
}
