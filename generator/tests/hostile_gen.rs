//! Issue 20's classes of hostile input for `gen`, one test each: clips that show no motion
//! within the frame (whatever the parameter that made them), a name given twice, a bad
//! `--out` (bad input, exit 2), perturbation levels, and perturbed sets that stay seeded; and
//! issue 50's: values whose motion overflows, a refusal that leaves no folder, a full
//! standard output, a law too long to walk, and Ctrl-C in the middle of a write.

mod util;

use physvid_testkit::stderr;
use std::path::Path;
use util::{gen, gen_scene};

#[test]
fn clips_that_show_no_motion_are_refused_and_nothing_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    for (scene, set) in [
        ("free-fall", "g=1e-9"),
        ("free-fall", "h0=1e6"),
        ("free-fall", "radius=1e-9"),
        ("led", "gamma=1e-9"),
        ("torricelli", "k=1e-12"),
        ("sliding-block", "travel=1e300"),
        ("sliding-block", "g=1e-300"),
    ] {
        gen_scene(scene, &out)
            .args(["--set", set, "--samples", "8"])
            .bad_input("shows no motion within the frame");
        assert!(!out.exists(), "a refusal leaves no folder: {scene} {set}");
    }
    // The same scenes at their own settings still render.
    gen_scene("led", &out).args(["--samples", "8"]).ok();
}

#[test]
fn a_name_given_twice_and_a_bad_out_are_bad_input() {
    let tmp = tempfile::tempdir().unwrap();
    gen_scene("pendulum", &tmp.path().join("g"))
        .args(["--set", "length=0.5,length=2"])
        .bad_input("'length' is given twice");
    gen_scene("pendulum", &tmp.path().join("g"))
        .args(["--set", "length=nan"])
        .bad_input("finite");
    let file = tmp.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    for out in [file.clone(), file.join("under")] {
        gen_scene("intensity", &out)
            .args(["--samples", "4"])
            .bad_input("--out");
    }
    #[cfg(unix)]
    {
        let link = tmp.path().join("dangling");
        std::os::unix::fs::symlink(tmp.path().join("nowhere"), &link).unwrap();
        gen_scene("intensity", &link)
            .args(["--samples", "4"])
            .bad_input("symbolic link to nothing");
    }
}

#[test]
fn perturbations_are_levelled_seeded_and_recorded() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    gen_scene("rod", &tmp.path().join("bad"))
        .args(["--perturb", "shake:6"])
        .bad_input("1 to 5");
    gen_scene("rod", &tmp.path().join("bad"))
        .args(["--perturb", "wobble:1"])
        .bad_input("not a perturbation");
    for (dir, threads) in [(&a, "1"), (&b, "4")] {
        gen_scene("position", dir)
            .args(["--samples", "12", "--size", "24", "--threads", threads])
            .args(["--perturb", "distractors:3,shake:2,light:2,noise:1"])
            .ok();
    }
    let frames = |d: &std::path::Path| std::fs::read(d.join("frames.npy")).unwrap();
    assert_eq!(frames(&a), frames(&b), "the same bytes on 1 and 4 threads");
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("meta.json")).unwrap()).unwrap();
    let names: Vec<&str> = meta["perturbations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["distractors", "light", "shake", "noise"]);
    // The motion is the clean set's: the same latents.
    let clean = tmp.path().join("clean");
    gen_scene("position", &clean)
        .args(["--samples", "12", "--size", "24"])
        .ok();
    let clean_meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(clean.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["latents"], clean_meta["latents"]);
    assert_ne!(frames(&a), frames(&clean));
}

#[test]
fn a_truth_estimate_could_not_read_is_refused_at_gen() {
    // An LED dimming at γ = 1e308 went dark from its second frame: written, then refused by
    // estimate as no physical value. Refused here, with estimate's words, and nothing written.
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    gen_scene("led", &out)
        .args(["--set", "gamma=1e308", "--samples", "4"])
        .bad_input("gamma=1e308: not a physical value (within ±1e15)");
    assert!(!out.exists(), "a refusal leaves no folder");
}

#[test]
fn values_whose_motion_overflows_are_refused_not_written_as_nulls() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    gen_scene("sliding-block", &out)
        .args(["--set", "travel=1e308", "--samples", "4"])
        .bad_input("overflows");
    gen_scene("pendulum", &out)
        .args(["--set", "damping=1e6", "--samples", "4", "--size", "16"])
        .bad_input("not finite");
    assert!(!out.exists(), "a refusal leaves no folder");
}

#[test]
fn a_full_standard_output_is_an_error_not_a_panic() {
    let tmp = tempfile::tempdir().unwrap();
    let o = gen_scene("intensity", &tmp.path().join("x"))
        .args(["--samples", "4", "--size", "16"])
        .stdout_to(Path::new("/dev/full"))
        .output();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("standard output"), "{}", stderr(&o));
}

#[test]
fn a_law_too_long_to_walk_is_refused_before_it_is_built() {
    let tmp = tempfile::tempdir().unwrap();
    let model = tmp.path().join("long.toml");
    let terms = vec!["x"; 30_000].join(" + ");
    std::fs::write(
        &model,
        format!(
            "name = \"long\"\n[parameters]\nk = {{ start = 1.0 }}\n[state]\nx = \"v\"\n\
             v = \"-k*({terms})\"\n[observed]\nlatent = [\"x\"]\n[initial]\nx = [0.5, 1.0]\n\
             v = [-1.0, 1.0]\n"
        ),
    )
    .unwrap();
    gen()
        .args(["--scenario", "position", "--model"])
        .arg(&model)
        .out(&tmp.path().join("x"))
        .bad_input("tokens");
}

#[cfg(unix)]
#[test]
fn ctrl_c_in_the_middle_of_a_write_leaves_no_folder_and_no_partial_file() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    let child = gen_scene("position", &out)
        .args(["--samples", "4000", "--size", "64", "--threads", "1"])
        .spawn();
    let started = std::time::Instant::now();
    while !out.exists() && started.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    // SAFETY: kill has no memory effects.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(!out.exists(), "the folder this run made is gone");
}
