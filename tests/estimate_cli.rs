//! End-to-end tests of the real `estimate` binary on data made by the real `gen`: recovery,
//! determinism, the MSE-only collapse, bad input, and the output files.

use physvid_e2e::{
    assert_one_line_error, estimate_bin, estimate_of, gen_dataset, read_report, run, stderr,
};
use std::path::Path;

/// A small intensity set: 200 clips of 32×32 (fast, still enough to recover the parameters).
fn small_set(dir: &Path, scenario: &str) -> String {
    gen_dataset(
        dir,
        scenario,
        &["--samples", "200", "--size", "32", "--seed", "5"],
    )
}

#[test]
fn recovers_gamma0_and_gamma1_on_a_small_intensity_set() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(&tmp.path().join("data"), "intensity");
    let out = tmp.path().join("run");
    let o = run(
        &estimate_bin(),
        &[&data, "--out", out.to_str().unwrap(), "--threads", "2"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(
        table.contains("gamma0") && table.contains("rel. error"),
        "{table}"
    );
    let r = read_report(&out);
    let (g0, g1) = (estimate_of(&r, "gamma0"), estimate_of(&r, "gamma1"));
    assert!((g0 / 4.0016 - 1.0).abs() < 0.01, "gamma0 {g0}");
    assert!((g1 / 0.08 - 1.0).abs() < 0.10, "gamma1 {g1}");
    assert_eq!(r["stop"]["kind"], "early-stop", "the early stop fires");
    assert!(!r["latent_collapsed"].as_bool().unwrap());
    for f in [
        "report.json",
        "metrics.csv",
        "parameters.png",
        "latents.png",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let csv = std::fs::read_to_string(out.join("metrics.csv")).unwrap();
    assert!(
        csv.starts_with("epoch,train_loss,val_loss,val_mse,val_rel_mse,latent_std,gamma0,gamma1")
    );
    assert_eq!(
        csv.lines().count() - 1,
        r["epochs_run"].as_u64().unwrap() as usize
    );
    assert!(r["libtorch_version"].as_str().unwrap().starts_with("2."));
}

#[test]
fn same_seed_gives_the_same_estimates_and_another_seed_does_not() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(&tmp.path().join("data"), "position");
    let mut estimates = Vec::new();
    for (k, seed) in ["3", "3", "4"].iter().enumerate() {
        let out = tmp.path().join(format!("run{k}"));
        let o = run(
            &estimate_bin(),
            &[
                &data,
                "--out",
                out.to_str().unwrap(),
                "--epochs",
                "6",
                "--seed",
                seed,
                "--threads",
                "2",
                "--quiet",
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        let r = read_report(&out);
        estimates.push((estimate_of(&r, "gamma0"), estimate_of(&r, "gamma1")));
    }
    assert!((estimates[0].0 - estimates[1].0).abs() <= 1e-6 * estimates[0].0.abs());
    assert!((estimates[0].1 - estimates[1].1).abs() <= 1e-6 * estimates[0].1.abs().max(1e-3));
    assert_ne!(estimates[0], estimates[2], "the seed must matter");
}

#[test]
fn mse_only_loss_collapses_the_latent_and_the_report_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(&tmp.path().join("data"), "intensity");
    let out = tmp.path().join("run");
    // From the default start alone, as the paper trains: with the spectral start the physics
    // fits from the first epochs and the latent shrinks much more slowly.
    let o = run(
        &estimate_bin(),
        &[
            &data,
            "--out",
            out.to_str().unwrap(),
            "--loss",
            "mse",
            "--single-start",
            "--epochs",
            "40",
            "--threads",
            "2",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_report(&out);
    assert!(
        r["latent_collapsed"].as_bool().unwrap(),
        "latent std {}",
        r["latent_std"]
    );
    let history = r["history"].as_array().unwrap();
    let first_std = history[0]["latent_std"].as_f64().unwrap();
    let last_std = history.last().unwrap()["latent_std"].as_f64().unwrap();
    assert!(last_std < 0.1 * first_std, "{first_std} → {last_std}");
    assert!(stderr(&o).contains("collapsed"), "{}", stderr(&o));
}

#[test]
fn bare_npy_needs_dt_and_model_and_then_works() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "20", "--size", "16"],
    );
    let npy = format!("{data}/frames.npy");
    let out = tmp.path().join("run");
    let o = run(&estimate_bin(), &[&npy, "--out", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--dt"), "{}", stderr(&o));
    let o = run(
        &estimate_bin(),
        &[&npy, "--dt", "0.2", "--out", out.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--model"), "{}", stderr(&o));
    let o = run(
        &estimate_bin(),
        &[
            &npy,
            "--dt",
            "0.2",
            "--model",
            "damped-oscillator",
            "--epochs",
            "3",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_report(&out);
    assert!(
        r["parameters"][0]["truth"].is_null(),
        "no ground truth without metadata"
    );
}

fn write_npy(path: &Path, descr: &str, shape: &str, data: &[u8]) {
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    bytes.extend_from_slice(dict.as_bytes());
    bytes.extend_from_slice(data);
    std::fs::write(path, bytes).unwrap();
}

fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

#[test]
fn bad_input_gets_a_one_line_error_and_exit_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let data = gen_dataset(
        &t.join("data"),
        "intensity",
        &["--samples", "6", "--size", "8", "--frames", "5"],
    );
    let p = |name: &str| t.join(name).to_str().unwrap().to_string();
    write_npy(
        &t.join("f8.npy"),
        "<f8",
        "(2, 3, 1, 2, 2)",
        &[0u8; 2 * 3 * 4 * 8],
    );
    write_npy(
        &t.join("rank3.npy"),
        "<f4",
        "(2, 3, 4)",
        &f32_bytes(&[0.0; 24]),
    );
    std::fs::write(
        t.join("garbage.npy"),
        b"\x93NUMPY\x01\x00\x10\x00{'descr': oops}\n",
    )
    .unwrap();
    write_npy(
        &t.join("short.npy"),
        "<f4",
        "(2, 2, 1, 2, 2)",
        &f32_bytes(&[0.5; 16]),
    );
    let mut nan = vec![0.5f32; 2 * 4 * 4];
    nan[9] = f32::NAN;
    write_npy(
        &t.join("nan.npy"),
        "<f4",
        "(2, 4, 1, 2, 2)",
        &f32_bytes(&nan),
    );
    // meta.json inconsistent with frames.npy, and one naming an unknown model.
    let bad_meta = t.join("badmeta");
    std::fs::create_dir(&bad_meta).unwrap();
    std::fs::copy(format!("{data}/frames.npy"), bad_meta.join("frames.npy")).unwrap();
    let meta = std::fs::read_to_string(format!("{data}/meta.json")).unwrap();
    std::fs::write(
        bad_meta.join("meta.json"),
        meta.replacen("\"dt\": 0.2", "\"dt\": -0.2", 1),
    )
    .unwrap();
    let unknown = t.join("unknown");
    std::fs::create_dir(&unknown).unwrap();
    std::fs::copy(format!("{data}/frames.npy"), unknown.join("frames.npy")).unwrap();
    std::fs::write(
        unknown.join("meta.json"),
        meta.replacen("damped-oscillator", "spring-pendulum", 1),
    )
    .unwrap();
    let inconsistent = t.join("inconsistent");
    std::fs::create_dir(&inconsistent).unwrap();
    std::fs::copy(
        format!("{data}/frames.npy"),
        inconsistent.join("frames.npy"),
    )
    .unwrap();
    std::fs::write(
        inconsistent.join("meta.json"),
        meta.replacen("\"shape\": [\n    6,", "\"shape\": [\n    7,", 1),
    )
    .unwrap();

    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec![p("missing")], "missing"),
        (
            vec![
                p("f8.npy"),
                "--dt".into(),
                "0.2".into(),
                "--model".into(),
                "damped-oscillator".into(),
            ],
            "'<f8'",
        ),
        (
            vec![
                p("rank3.npy"),
                "--dt".into(),
                "0.2".into(),
                "--model".into(),
                "damped-oscillator".into(),
            ],
            "rank 3",
        ),
        (
            vec![
                p("garbage.npy"),
                "--dt".into(),
                "0.2".into(),
                "--model".into(),
                "damped-oscillator".into(),
            ],
            "not a valid .npy",
        ),
        (
            vec![
                p("short.npy"),
                "--dt".into(),
                "0.2".into(),
                "--model".into(),
                "damped-oscillator".into(),
            ],
            "at least 3",
        ),
        (
            vec![
                p("nan.npy"),
                "--dt".into(),
                "0.2".into(),
                "--model".into(),
                "damped-oscillator".into(),
            ],
            "not finite",
        ),
        (vec![bad_meta.to_str().unwrap().into()], "dt is -0.2"),
        (vec![unknown.to_str().unwrap().into()], "spring-pendulum"),
        (vec![inconsistent.to_str().unwrap().into()], "shape"),
        (
            vec![data.clone(), "--model".into(), "pendulum-of-doom".into()],
            "--model",
        ),
        (vec![data.clone(), "--dt".into(), "0".into()], "--dt"),
        (vec![data.clone(), "--dt".into(), "-1".into()], "--dt"),
        (
            vec![data.clone(), "--dt".into(), "0.3".into()],
            "contradicts",
        ),
        (
            vec![data.clone(), "--init".into(), "gamma7=1".into()],
            "gamma7",
        ),
        (
            vec![data.clone(), "--init".into(), "gamma0=-1".into()],
            "gamma0",
        ),
    ];
    let out = t.join("run");
    for (args, needle) in cases {
        let mut full = args.clone();
        full.extend([
            "--out".to_string(),
            out.to_str().unwrap().to_string(),
            "--epochs".into(),
            "1".into(),
        ]);
        let refs: Vec<&str> = full.iter().map(String::as_str).collect();
        assert_one_line_error(&estimate_bin(), &refs, needle);
    }
    if !cuda_visible() {
        let o = run(
            &estimate_bin(),
            &[&data, "--device", "cuda", "--out", out.to_str().unwrap()],
        );
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("--device cuda"), "{}", stderr(&o));
    }
}

/// Whether this machine has an NVIDIA GPU (then `--device cuda` is not an error).
fn cuda_visible() -> bool {
    Path::new("/dev/nvidia0").exists()
}

#[test]
fn help_describes_every_flag() {
    let o = run(&estimate_bin(), &["--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    for flag in [
        "--dt",
        "--model",
        "--epochs",
        "--batch-size",
        "--lr",
        "--lr-phys",
        "--init",
        "--integrator",
        "--rollout-start",
        "--loss",
        "--seed",
        "--device",
        "--threads",
        "--out",
        "--quiet",
        "--encoder",
        "--ensemble",
        "--fps",
        "--crop",
        "--start",
        "--end",
        "--size",
        "--frames-per-clip",
        "--stride",
        "--hop",
        "--preview",
    ] {
        assert!(help.contains(flag), "--help lacks {flag}");
    }
}

#[test]
fn a_nan_loss_stops_with_the_last_good_parameters_and_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "40", "--size", "16"],
    );
    let out = tmp.path().join("run");
    let o = run(
        &estimate_bin(),
        &[
            &data,
            "--out",
            out.to_str().unwrap(),
            "--lr",
            "1e6",
            "--lr-phys",
            "1e6",
            "--epochs",
            "20",
            "--single-start",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        !stdout.to_lowercase().contains("nan") && !stdout.contains("inf"),
        "{stdout}"
    );
    assert!(stderr(&o).contains("NaN or infinite"), "{}", stderr(&o));
    let r = read_report(&out);
    assert_eq!(r["stop"]["kind"], "non-finite-loss");
    assert!(estimate_of(&r, "gamma0").is_finite() && estimate_of(&r, "gamma1").is_finite());
}

#[test]
fn a_missing_calibration_gives_latent_units_and_says_why() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "torricelli",
        &["--samples", "30", "--size", "16"],
    );
    let npy = format!("{data}/frames.npy");
    let out = tmp.path().join("run");
    let o = run(
        &estimate_bin(),
        &[
            &npy,
            "--model",
            "torricelli",
            "--dt",
            "1",
            "--epochs",
            "3",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("--reference"), "{}", stderr(&o));
    let r = read_report(&out);
    let units: Vec<&str> = r["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["units"].as_str().unwrap())
        .collect();
    assert!(units.iter().all(|u| *u == "latent"), "{units:?}");
    // With reference frames the same run answers k in SI units.
    let o = run(
        &estimate_bin(),
        &[
            &npy,
            "--model",
            "torricelli",
            "--dt",
            "1",
            "--epochs",
            "3",
            "--reference",
            "0:0=0.05,1:19=0.02",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_report(&out);
    assert_eq!(r["parameters"][0]["name"], "k");
    assert_eq!(r["parameters"][0]["units"], "SI");
    let o = run(
        &estimate_bin(),
        &[
            &npy,
            "--model",
            "torricelli",
            "--dt",
            "1",
            "--reference",
            "99:0=0.05,1:19=0.02",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--reference 99:0"), "{}", stderr(&o));
}

#[test]
fn an_ensemble_reports_the_spread_over_seeds() {
    let tmp = tempfile::tempdir().unwrap();
    let data = small_set(&tmp.path().join("data"), "intensity");
    let out = tmp.path().join("run");
    let o = run(
        &estimate_bin(),
        &[
            &data,
            "--ensemble",
            "3",
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("ensemble of 3"));
    let r = read_report(&out);
    let e = &r["ensemble"];
    assert_eq!(e["members"], 3);
    assert_eq!(e["seeds"], serde_json::json!([0, 1, 2]));
    let g0 = &e["values"][0];
    assert_eq!(g0["name"], "gamma0");
    let values: Vec<f64> = g0["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(values.len(), 3);
    // Member 0 is the run the rest of the report describes; different seeds differ.
    assert_eq!(values[0], estimate_of(&r, "gamma0"));
    assert!(g0["std"].as_f64().unwrap() > 0.0);
    assert!((g0["mean"].as_f64().unwrap() / 4.0016 - 1.0).abs() < 0.01);
    let o = run(
        &estimate_bin(),
        &[&data, "--ensemble", "0", "--out", out.to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--ensemble 0"), "{}", stderr(&o));
}
