//! End-to-end tests of `estimate` on the two-body spring: k and the rest length in pixels from a
//! short run on a small set, the latent checked against the truth in the plane; what the spring
//! refuses.

mod util;

use util::{estimate_of, gen_dataset, read_report, Estimate};

#[test]
fn spring_finds_k_and_the_rest_length_in_pixels_on_a_small_set() {
    // 100 clips, 30 epochs of 10 steps (about a minute on 2 cores): measured k +0.07 %,
    // rest length +0.9 %, relative-vector R² 0.998.
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(&tmp.path().join("data"), "spring", &["--samples", "100"]);
    let out = tmp.path().join("run");
    Estimate::new(&data)
        .args(["--epochs", "30", "--batch-size", "8", "--single-start"])
        .out(&out)
        .quiet()
        .ok();
    let r = read_report(&out);
    let fit = &r["latent_vs_truth"];
    let r2 = fit["relative"]["r2"].as_f64().expect("a planar fit");
    assert!(r2 > 0.98, "the relative vector is not found: R² {r2}");
    assert_eq!(fit["bodies"].as_array().unwrap().len(), 2);
    let names: Vec<&str> = r["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["k", "rest_length", "rest_length_latent"]);
    for (name, truth) in [("k", 2.0), ("rest_length", 24.0)] {
        let v = estimate_of(&r, name);
        assert!((v / truth - 1.0).abs() < 0.05, "{name} {v} (truth {truth})");
    }
    assert!(out.join("latents.png").exists());
}

#[test]
fn what_the_spring_refuses() {
    let tmp = tempfile::tempdir().unwrap();
    let spring = gen_dataset(
        &tmp.path().join("spring"),
        "spring",
        &["--samples", "4", "--frames", "6"],
    );
    let scalar = gen_dataset(
        &tmp.path().join("scalar"),
        "intensity",
        &["--samples", "4", "--size", "8", "--frames", "5"],
    );
    let out = tmp.path().join("never");
    let run = |input: &str| Estimate::new(input).out(&out).args(["--epochs", "1"]);
    run(&spring)
        .args(["--integrator", "euler"])
        .bad_input("--integrator euler");
    run(&spring)
        .args(["--reference", "0:0=3"])
        .bad_input("X1/Y1/X2/Y2");
    run(&spring)
        .args(["--reference", "0:0=1/2/3/4,9:0=2/3/4/5"])
        .bad_input("9:0");
    run(&scalar)
        .args(["--encoder", "keypoints"])
        .bad_input("keypoints");
    run(&scalar)
        .args(["--reference", "0:0=1/2/3/4,1:0=2/3/4/5"])
        .bad_input("--reference");
    assert!(!out.exists());
}
