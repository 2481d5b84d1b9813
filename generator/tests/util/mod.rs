//! Test helpers: `gen` as a `TestCommand`, file listing, the fixtures folder. Each test file
//! uses part of it.
#![allow(dead_code)]

#[allow(unused_imports)]
pub use physvid_testkit::stderr;
pub use physvid_testkit::TestCommand;
use std::path::{Path, PathBuf};

/// The `gen` binary built for these tests.
pub fn bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_gen"))
}

/// `gen` with no arguments yet.
pub fn gen() -> TestCommand {
    TestCommand::new(bin())
}

/// `gen --scenario SCENARIO --out OUT`.
pub fn gen_scene(scenario: &str, out: &Path) -> TestCommand {
    gen().args(["--scenario", scenario]).out(out)
}

/// File names in `dir`, sorted.
pub fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// The committed fixtures folder.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures")
}
