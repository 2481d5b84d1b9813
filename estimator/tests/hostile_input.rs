//! End-to-end tests of the hostile inputs of issue 14 that used to hang, crash or print a
//! number that is not an answer: absurd dt, thread counts, starts and learning rates get one
//! line and exit code 2; a training that diverges gets exit code 3 and writes nothing.

mod util;

use physvid_shared::outdir::{OutputDir, Wait};
use std::path::Path;
use util::{f32_bytes, gen_dataset, stderr, write_npy, Estimate, TestCommand};

/// A bare `.npy` of 12 clips × 20 frames of 8×8 deterministic noise.
fn noise_npy(dir: &Path) -> String {
    let path = dir.join("noise.npy");
    let values: Vec<f32> = (0..12 * 20 * 64)
        .map(|i| (i as f32 * 0.618_034).fract() * 0.8 + 0.1)
        .collect();
    write_npy(&path, "<f4", "(12, 20, 1, 8, 8)", &f32_bytes(&values));
    path.display().to_string()
}

/// `estimate NPY` as a damped oscillator at dt 0.2 for `epochs` epochs.
fn oscillator(npy: &str, epochs: &str) -> TestCommand {
    Estimate::new(npy).args([
        "--model",
        "damped-oscillator",
        "--dt",
        "0.2",
        "--epochs",
        epochs,
    ])
}

#[test]
fn absurd_dt_threads_starts_and_rates_are_refused_before_training() {
    let tmp = tempfile::tempdir().unwrap();
    let npy = noise_npy(tmp.path());
    let out = tmp.path().join("run");
    let bare = |model: &str, dt: &str| {
        Estimate::new(&npy)
            .args(["--model", model, "--dt", dt])
            .out(&out)
    };
    // Used to spin for minutes drawing the plot (1e308), to run without end (the pendulum's
    // sub-steps), or to print −1e58 or NaN (1e-30).
    bare("damped-oscillator", "1e308").bad_input("--dt 1e308 s: outside");
    bare("damped-oscillator", "1e6").bad_input("outside");
    bare("free-fall", "1e-30").bad_input("--dt 1e-30 s: outside");
    bare("pendulum", "1e4").bad_input("pendulum takes dt ≤ 10 s");
    // Used to overflow the stack or crash libgomp.
    bare("damped-oscillator", "0.2")
        .args(["--threads", "100000"])
        .bad_input("must be from 1 to 256");
    // Used to print `gamma1 inf … +inf %`.
    bare("damped-oscillator", "0.2")
        .args(["--single-start", "--init", "gamma1=1e300"])
        .bad_input("--init gamma1=1e300: must be a finite number");
    // Used to exit 0 with the starting values as estimates.
    bare("damped-oscillator", "0.2")
        .args(["--lr", "1e30"])
        .bad_input("--lr 1e30: must be at most 1");
    bare("damped-oscillator", "0.2")
        .args(["--lr-phys", "1e30"])
        .bad_input("--lr-phys 1e30: must be at most 1");
    assert!(!out.exists(), "nothing written for refused input");
}

#[test]
fn dt_in_meta_json_is_held_to_the_same_range() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "6", "--size", "8"],
    );
    let meta = Path::new(&data).join("meta.json");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&meta).unwrap()).unwrap();
    json["dt"] = serde_json::json!(1e308);
    std::fs::write(&meta, serde_json::to_string(&json).unwrap()).unwrap();
    Estimate::new(&data)
        .out(&tmp.path().join("run"))
        .bad_input("meta.json's dt 1e308 s: outside");
}

#[test]
fn a_diverged_training_exits_3_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let npy = noise_npy(tmp.path());
    let out = tmp.path().join("run");
    let o = oscillator(&npy, "3")
        .args(["--single-start", "--init", "gamma1=1e14"])
        .out(&out)
        .quiet()
        .output();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("no estimate: training diverged"), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(o.stdout.is_empty(), "no table of starting values");
    assert!(!out.exists(), "nothing written");
}

#[test]
fn out_is_checked_before_training_and_an_old_run_is_replaced_wholly() {
    let tmp = tempfile::tempdir().unwrap();
    let npy = noise_npy(tmp.path());
    let run = |out: &Path| oscillator(&npy, "2").out(out).quiet();
    let file = tmp.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    run(&file).bad_input("is a file or device, not a directory");
    run(&file.join("run")).bad_input("is a file, not a directory");
    run(Path::new("/dev/null")).bad_input("not a directory");
    run(Path::new("/proc/x")).bad_input("cannot write in /proc");
    #[cfg(unix)]
    {
        let link = tmp.path().join("dangling");
        std::os::unix::fs::symlink(tmp.path().join("nowhere"), &link).unwrap();
        run(&link).bad_input("symbolic link to nothing");
    }
    // An earlier recording's run (its files written as the tool writes them) left a
    // timeline: a dataset run over it leaves none of it.
    let out = tmp.path().join("run");
    let olds = ["timeline.csv", "clips.png", "report.json"];
    let mut earlier =
        OutputDir::open("--out", &out, "estimate", &olds, false, Wait::Turns).unwrap();
    for old in olds {
        earlier.write(old, b"old").unwrap();
    }
    earlier.finish();
    run(&out).estimated();
    assert!(!out.join("timeline.csv").exists() && !out.join("clips.png").exists());
    let report = std::fs::read_to_string(out.join("report.json")).unwrap();
    assert!(report.starts_with('{'), "the new report");
}
