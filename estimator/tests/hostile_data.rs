//! End-to-end tests of the hostile inputs of issue 14 that used to be accepted in silence or
//! answered with the wrong words: flags that do not apply, reference points that give no scale,
//! misnamed files, frames in which nothing moves, and meta.json truth that contradicts its
//! model. Each gets one line and exit code 2 before any training.

mod util;

use std::path::Path;
use util::{f32_bytes, gen_dataset, write_npy, Estimate};

/// A bare `.npy` of 6 clips × 8 frames of 8×8 pixels, all `value`.
fn flat_npy(path: &Path, value: f32) {
    write_npy(
        path,
        "<f4",
        "(6, 8, 1, 8, 8)",
        &f32_bytes(&vec![value; 6 * 8 * 64]),
    );
}

/// Six clips of `scene` at `size` px rendered into `tmp/data`.
fn small_set(tmp: &Path, scene: &str, size: &str) -> String {
    gen_dataset(
        &tmp.join("data"),
        scene,
        &["--samples", "6", "--size", size],
    )
}

/// Rewrites `DIR/meta.json` through `edit`.
fn edit_meta(dir: &str, edit: impl FnOnce(&mut serde_json::Value)) {
    let path = Path::new(dir).join("meta.json");
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    edit(&mut json);
    std::fs::write(&path, serde_json::to_string(&json).unwrap()).unwrap();
}

#[test]
fn flags_that_do_not_apply_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(tmp.path(), "intensity", "8");
    let out = tmp.path().join("run");
    let run = |args: &[&str]| Estimate::new(&data).args(args.to_vec()).out(&out);
    for flag in [
        &["--fps", "30"][..],
        &["--crop", "0,0,4,4"],
        &["--stride", "2"],
        &["--preview"],
    ] {
        run(flag).bad_input(&format!("{}: applies to recordings", flag[0]));
    }
    run(&["--incline-deg", "30"]).bad_input("--incline-deg: damped-oscillator does not use it");
    run(&["--reference", "0:0=1,1:0=2"])
        .bad_input("--reference: damped-oscillator does not use it");
    run(&["--g", "9.8"]).bad_input("it applies to pendulum, sliding-block");
    // Reference times are for recordings; a data set's frames are counted in clips.
    let pendulum = small_set(&tmp.path().join("p"), "pendulum", "16");
    Estimate::new(&pendulum)
        .args(["--reference", "1s=0.1,2s=0.2"])
        .out(&out)
        .bad_input("--reference 1s=0.1: times apply to recordings");
    assert!(!out.exists());
}

#[test]
fn reference_points_that_give_no_scale_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(tmp.path(), "torricelli", "16");
    let out = tmp.path().join("run");
    let refs = |r: &str| Estimate::new(&data).args(["--reference", r]).out(&out);
    refs("0:0=0.05").bad_input("one frame (0:0) gives no scale");
    refs("0:0=0.05,0:0=0.02").bad_input("clip 0 frame 0 is given twice");
    refs("0:0=0.05,1:3=0.05").bad_input("every frame has the value 0.05");
    refs("0:0=1e300,1:3=0.02").bad_input("0:0=1e300: must be within");
    refs("0:0=-0.01,1:3=0.02").bad_input("below zero, and a water level");
    refs("0:0=inf,1:3=0.02").bad_input("inf is not a finite number");
    assert!(!out.exists());
}

#[test]
fn misnamed_inputs_get_the_right_words() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let out = t.join("run");
    let osc = |input: &Path| {
        Estimate::new(input)
            .args(["--model", "damped-oscillator", "--dt", "0.2"])
            .out(&out)
    };
    // A directory named like an array: it used to be blamed on --dt as a recording.
    std::fs::create_dir(t.join("clips.npy")).unwrap();
    osc(&t.join("clips.npy")).bad_input("neither a gen dataset");
    // frames.npy that is a directory: it used to be "shorter than the .npy preamble".
    let ds = t.join("ds");
    std::fs::create_dir_all(ds.join("frames.npy")).unwrap();
    std::fs::write(ds.join("meta.json"), "{}").unwrap();
    Estimate::new(&ds)
        .out(&out)
        .bad_input("frames.npy is not a valid .npy file: it is a directory");
    // A negative shape entry: it used to be "not an integer".
    let neg = t.join("neg.npy");
    write_npy(&neg, "<f4", "(6, -8, 1, 8, 8)", &[]);
    osc(&neg).bad_input("shape entry '-8' is negative");
    // --fps beyond any camera: the stride used to wrap around to 18446744073709551615.
    let folder = t.join("frames");
    std::fs::create_dir(&folder).unwrap();
    image::GrayImage::new(8, 8)
        .save(folder.join("f1.png"))
        .unwrap();
    Estimate::new(&folder)
        .args(["--model", "pendulum", "--fps", "1e300"])
        .out(&out)
        .bad_input("--fps 1e300: must be > 0 and at most 1e7");
    assert!(!out.exists());
    // An array without the .npy extension is read as one (by its magic string), not
    // refused as a recording for --dt.
    let bare = t.join("clips");
    let values: Vec<f32> = (0..6 * 8 * 64)
        .map(|i| (i as f32 * 0.618_034).fract())
        .collect();
    write_npy(&bare, "<f4", "(6, 8, 1, 8, 8)", &f32_bytes(&values));
    osc(&bare).args(["--epochs", "1"]).quiet().estimated();
}

#[test]
fn frames_in_which_nothing_moves_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("run");
    for (value, shown) in [(0.5f32, "0.5"), (-0.0, "-0")] {
        let npy = tmp.path().join(format!("flat{shown}.npy"));
        flat_npy(&npy, value);
        Estimate::new(&npy)
            .args(["--model", "damped-oscillator", "--dt", "0.2"])
            .out(&out)
            .bad_input(&format!("nothing moves: within every clip each frame equals the first (every pixel {shown})"));
    }
    assert!(!out.exists());
}

#[test]
fn ground_truth_that_contradicts_its_model_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(tmp.path(), "intensity", "8");
    let out = tmp.path().join("run");
    let check = |edit: &dyn Fn(&mut serde_json::Value), needle: &str| {
        let copy = tmp.path().join("copy");
        let _ = std::fs::remove_dir_all(&copy);
        std::fs::create_dir(&copy).unwrap();
        for f in ["frames.npy", "meta.json"] {
            std::fs::copy(Path::new(&data).join(f), copy.join(f)).unwrap();
        }
        let copy = copy.to_str().unwrap().to_string();
        edit_meta(&copy, edit);
        Estimate::new(&copy).out(&out).bad_input(needle);
    };
    // Used to be reported as a −198 % error, and as a 300-digit number.
    check(
        &|m| m["model"]["parameters"]["gamma0"] = (-4.0).into(),
        "gamma0 = -4: must be > 0 for damped-oscillator",
    );
    check(
        &|m| m["model"]["parameters"]["gamma0"] = 1e300.into(),
        "gamma0 = 1e300: not a physical value",
    );
    // The oscillator's truth under model led: it used to be dropped in silence.
    check(
        &|m| m["model"]["name"] = "led".into(),
        "names none of led's values (gamma)",
    );
    assert!(!out.exists());
}
