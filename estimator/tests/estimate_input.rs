//! End-to-end tests of what `estimate` accepts: bare `.npy` arrays (with --dt and --model),
//! malformed and inconsistent input (one line, exit code 2), and calibrations.

mod util;

use std::path::Path;
use util::{f32_bytes, gen_dataset, read_report, stderr, write_npy, Estimate};

#[test]
fn bare_npy_needs_dt_and_then_works() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "20", "--size", "16"],
    );
    let npy = format!("{data}/frames.npy");
    let out = tmp.path().join("run");
    let o = Estimate::new(&npy).out(&out).output();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--dt"), "{}", stderr(&o));
    Estimate::new(&npy)
        .args([
            "--dt",
            "0.2",
            "--model",
            "damped-oscillator",
            "--epochs",
            "3",
        ])
        .out(&out)
        .quiet()
        .ok();
    let r = read_report(&out);
    assert!(
        r["parameters"][0]["truth"].is_null(),
        "no ground truth without metadata"
    );
}

/// A copy of dataset `data` in `dir` whose meta.json has `from` replaced by `to`.
fn edited_copy(data: &str, dir: &Path, from: &str, to: &str) -> String {
    std::fs::create_dir(dir).unwrap();
    std::fs::copy(format!("{data}/frames.npy"), dir.join("frames.npy")).unwrap();
    let meta = std::fs::read_to_string(format!("{data}/meta.json")).unwrap();
    std::fs::write(dir.join("meta.json"), meta.replacen(from, to, 1)).unwrap();
    dir.to_str().unwrap().to_string()
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
    let bad_meta = edited_copy(&data, &t.join("badmeta"), "\"dt\": 0.2", "\"dt\": -0.2");
    let unknown = edited_copy(
        &data,
        &t.join("unknown"),
        "damped-oscillator",
        "spring-pendulum",
    );
    let inconsistent = edited_copy(
        &data,
        &t.join("inconsistent"),
        "\"shape\": [\n    6,",
        "\"shape\": [\n    7,",
    );
    let out = t.join("run");
    let run = |input: &str| Estimate::new(input).out(&out).args(["--epochs", "1"]);
    let bare = |input: &str| run(input).args(["--dt", "0.2", "--model", "damped-oscillator"]);
    run(&p("missing")).bad_input("missing");
    bare(&p("f8.npy")).bad_input("'<f8'");
    bare(&p("rank3.npy")).bad_input("rank 3");
    bare(&p("garbage.npy")).bad_input("not a valid .npy");
    bare(&p("short.npy")).bad_input("at least 3");
    bare(&p("nan.npy")).bad_input("not finite");
    run(&bad_meta).bad_input("dt is -0.2");
    run(&unknown).bad_input("spring-pendulum");
    run(&inconsistent).bad_input("shape");
    run(&data)
        .args(["--model", "pendulum-of-doom"])
        .bad_input("--model");
    run(&data).args(["--dt", "0"]).bad_input("--dt");
    run(&data).args(["--dt", "-1"]).bad_input("--dt");
    run(&data).args(["--dt", "0.3"]).bad_input("contradicts");
    run(&data).args(["--init", "gamma7=1"]).bad_input("gamma7");
    run(&data).args(["--init", "gamma0=-1"]).bad_input("gamma0");
    if !cuda_visible() {
        let o = Estimate::new(&data)
            .args(["--device", "cuda"])
            .out(&out)
            .output();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("--device cuda"), "{}", stderr(&o));
    }
}

/// Whether this machine has an NVIDIA GPU (then `--device cuda` is not an error).
fn cuda_visible() -> bool {
    Path::new("/dev/nvidia0").exists()
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
    let torricelli = || Estimate::new(&npy).args(["--model", "torricelli", "--dt", "1"]);
    let o = torricelli()
        .args(["--epochs", "3"])
        .out(&out)
        .quiet()
        .estimated();
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
    torricelli()
        .args(["--epochs", "3", "--reference", "0:0=0.05,1:19=0.02"])
        .out(&out)
        .quiet()
        .estimated();
    let r = read_report(&out);
    assert_eq!(r["parameters"][0]["name"], "k");
    assert_eq!(r["parameters"][0]["units"], "SI");
    let o = torricelli()
        .args(["--reference", "99:0=0.05,1:19=0.02"])
        .out(&out)
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--reference 99:0"), "{}", stderr(&o));
}
