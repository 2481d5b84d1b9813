//! End-to-end tests of the Delfys75 systems: `gen` renders each system, default `estimate`
//! recovers its Table 4 parameter in SI units; a pendulum swinging at 60°; bad input.

mod util;

use std::path::Path;
use util::{estimate_of, gen_dataset, read_report, stderr, Estimate};

/// Runs default `estimate` on `data` into `out` and returns the report.
fn estimate(data: &str, out: &Path, extra: &[&str]) -> serde_json::Value {
    Estimate::new(data).out(out).quiet().args(extra).ok();
    read_report(out)
}

fn relative_error(report: &serde_json::Value, name: &str) -> f64 {
    let p = util::parameter(report, name);
    assert_eq!(p["units"], "SI", "{name} is not in SI units");
    p["relative_error"].as_f64().expect("truth known")
}

#[test]
fn each_first_order_and_falling_system_is_recovered_in_si_units_on_a_small_set() {
    let tmp = tempfile::tempdir().unwrap();
    // (scenario, setting, parameter, tolerance): 200 clips of 32×32 instead of 500 of 50×50.
    for (scenario, setting, name, tol) in [
        ("led", "3", "gamma", 0.02),
        ("torricelli", "3", "k", 0.02),
        ("sliding-block", "2", "mu", 0.03),
        ("free-fall", "1", "g", 0.03),
    ] {
        let data = gen_dataset(
            &tmp.path().join(scenario),
            scenario,
            &["--setting", setting, "--samples", "200", "--size", "32"],
        );
        let r = estimate(&data, &tmp.path().join(format!("{scenario}-run")), &[]);
        let err = relative_error(&r, name);
        assert!(
            err.abs() < tol,
            "{scenario}: {name} off by {:.2} %",
            err * 100.0
        );
        assert_eq!(r["model"], scenario);
        // No answer left in latent units, and the release is known where it matters.
        let warnings = r["warnings"].to_string();
        assert!(
            !warnings.contains("latent units") && !warnings.contains("clip_start_times"),
            "{scenario}: {warnings}"
        );
    }
}

#[test]
fn a_pendulum_swinging_at_60_degrees_gives_its_length() {
    // Every clip swings at 60°, where the period is 7 % longer than the small-angle one: a
    // small-angle block would find L about 14 % short.
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "pendulum",
        &[
            "--setting",
            "2",
            "--samples",
            "120",
            "--size",
            "40",
            "--set",
            "amplitude_min_deg=60,amplitude_max_deg=60",
        ],
    );
    let r = estimate(&data, &tmp.path().join("run"), &[]);
    let err = relative_error(&r, "length");
    assert!(err.abs() < 0.02, "L off by {:.2} %", err * 100.0);
}

#[test]
fn delfys_bad_input_gets_a_one_line_error_and_exit_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "pendulum",
        &["--samples", "10", "--size", "16"],
    );
    let out = tmp.path().join("run");
    for (args, needle) in [
        // A model that does not fit the data: meta.json says pendulum.
        (
            vec!["--model", "led"],
            "contradicts meta.json's model pendulum",
        ),
        // Parameters of another model, and an impossible start.
        (vec!["--init", "gamma=1"], "gamma"),
        (vec!["--init", "g_over_l=-3"], "g_over_l"),
        // A reference frame outside the data.
        (vec!["--reference", "0:99=0.1,1:0=0.2"], "--reference 0:99"),
        (vec!["--g", "-9.81"], "--g"),
        // The peer's residual loss is written for the oscillator only.
        (
            vec!["--loss", "residual+floor"],
            "--loss residual+floor: implemented for damped-oscillator only",
        ),
    ] {
        Estimate::new(&data)
            .out(&out)
            .args(["--epochs", "1"])
            .args(args)
            .bad_input(needle);
    }
}

#[test]
fn free_fall_without_start_times_warns_that_the_answer_is_not_identified() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "free-fall",
        &["--samples", "20", "--size", "16"],
    );
    let out = tmp.path().join("run");
    let npy = format!("{data}/frames.npy");
    let dt = (1.0f64 / 30.0).to_string();
    let o = Estimate::new(&npy)
        .args(["--model", "free-fall", "--dt", &dt, "--epochs", "2"])
        .out(&out)
        .quiet()
        .estimated();
    assert!(stderr(&o).contains("clip_start_times"), "{}", stderr(&o));
    let r = read_report(&out);
    assert!(estimate_of(&r, "acceleration_latent").is_finite());
}
