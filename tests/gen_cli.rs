//! End-to-end tests of the real `gen` binary: reproducibility across thread counts, bad input,
//! overwrite protection and crash safety of the dataset files.

use physvid_e2e::{gen_bin, run, stderr};
use std::path::Path;
use std::process::Command;

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn same_arguments_give_byte_identical_files_on_1_and_4_threads() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    for scenario in ["intensity", "position", "scale"] {
        let mut outputs = Vec::new();
        for threads in ["1", "4"] {
            let out = tmp.path().join(format!("{scenario}-{threads}"));
            let o = run(
                &gen,
                &[
                    "--scenario",
                    scenario,
                    "--out",
                    out.to_str().unwrap(),
                    "--samples",
                    "37",
                    "--frames",
                    "9",
                    "--size",
                    "24",
                    "--noise",
                    "0.05",
                    "--seed",
                    "11",
                    "--threads",
                    threads,
                ],
            );
            assert!(o.status.success(), "{}", stderr(&o));
            outputs.push(out);
        }
        assert_eq!(
            files(&outputs[0]),
            ["frames.npy", "meta.json", "preview.png"]
        );
        for name in ["frames.npy", "meta.json", "preview.png"] {
            let a = std::fs::read(outputs[0].join(name)).unwrap();
            let b = std::fs::read(outputs[1].join(name)).unwrap();
            assert!(a == b, "{scenario}/{name} differs between 1 and 4 threads");
        }
        // A different seed gives different frames.
        let other = tmp.path().join(format!("{scenario}-seed12"));
        let o = run(
            &gen,
            &[
                "--scenario",
                scenario,
                "--out",
                other.to_str().unwrap(),
                "--samples",
                "37",
                "--frames",
                "9",
                "--size",
                "24",
                "--noise",
                "0.05",
                "--seed",
                "12",
            ],
        );
        assert!(o.status.success());
        assert_ne!(
            std::fs::read(other.join("frames.npy")).unwrap(),
            std::fs::read(outputs[0].join("frames.npy")).unwrap()
        );
    }
}

#[test]
fn written_dataset_reads_back_with_its_ground_truth() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let o = run(
        &gen,
        &[
            "--scenario",
            "position",
            "--out",
            out.to_str().unwrap(),
            "--samples",
            "5",
            "--frames",
            "6",
            "--size",
            "16",
            "--dt",
            "0.1",
            "--omega",
            "3",
            "--zeta",
            "0.1",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("preview.png"), "{stdout}");
    let ds = physvid_shared::read_dataset(&out).unwrap();
    assert_eq!(ds.shape, [5, 6, 1, 16, 16]);
    let meta = ds.meta.unwrap();
    assert_eq!(meta.model.name, "damped-oscillator");
    assert!((meta.model.parameters["gamma0"] - 9.01).abs() < 1e-12);
    assert!((meta.model.parameters["gamma1"] - 0.2).abs() < 1e-12);
    assert_eq!(meta.dt, 0.1);
    assert!(ds.frames.iter().all(|v| (0.0..=1.0).contains(v)));
    // The npy header is what numpy writes for a C-order '<f4' array.
    let bytes = std::fs::read(out.join("frames.npy")).unwrap();
    let header = String::from_utf8_lossy(&bytes[10..128]);
    assert!(
        header.contains("'descr': '<f4', 'fortran_order': False, 'shape': (5, 6, 1, 16, 16)"),
        "{header}"
    );
}

#[test]
fn bad_input_gets_a_one_line_error_naming_the_flag_and_exit_code_2() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let o = out.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--scenario", "wobble", "--out", o], "--scenario"),
        (
            &["--scenario", "scale", "--out", o, "--size", "4"],
            "--size",
        ),
        (
            &["--scenario", "scale", "--out", o, "--frames", "2"],
            "--frames",
        ),
        (
            &["--scenario", "scale", "--out", o, "--samples", "0"],
            "--samples",
        ),
        (&["--scenario", "scale", "--out", o, "--dt", "0"], "--dt"),
        (&["--scenario", "scale", "--out", o, "--dt", "-0.1"], "--dt"),
        (&["--scenario", "scale", "--out", o, "--dt", "inf"], "--dt"),
        (&["--scenario", "scale", "--out", o, "--dt", "NaN"], "--dt"),
        (
            &["--scenario", "position", "--out", o, "--zeta", "-0.5"],
            "--zeta",
        ),
        (
            &["--scenario", "position", "--out", o, "--omega", "30"],
            "--omega",
        ),
        (
            &["--scenario", "position", "--out", o, "--noise", "2"],
            "--noise",
        ),
        (
            &[
                "--scenario",
                "scale",
                "--out",
                o,
                "--samples",
                "100000",
                "--size",
                "200",
            ],
            "8 GiB",
        ),
    ];
    for (args, needle) in cases {
        let r = run(&gen, args);
        let err = stderr(&r);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{args:?}: not one line: {err}"
        );
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    assert!(!out.exists(), "nothing is written on bad input");
}

#[test]
fn existing_non_empty_directory_needs_force() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("notes.txt"), "keep").unwrap();
    let dir = tmp.path().to_str().unwrap();
    let args = [
        "--scenario",
        "intensity",
        "--out",
        dir,
        "--samples",
        "3",
        "--size",
        "8",
    ];
    let r = run(&gen, &args);
    assert_eq!(r.status.code(), Some(2));
    assert!(stderr(&r).contains("--force"), "{}", stderr(&r));
    let mut forced = args.to_vec();
    forced.push("--force");
    let r = run(&gen, &forced);
    assert!(r.status.success(), "{}", stderr(&r));
    assert_eq!(
        files(tmp.path()),
        ["frames.npy", "meta.json", "notes.txt", "preview.png"]
    );
}

/// Runs gen under a file-size limit so the write of frames.npy fails part-way: killed by
/// SIGXFSZ (a crash) or, with the signal ignored, an EFBIG write error (a full disk).
fn gen_with_file_limit(dir: &Path, ignore_signal: bool) -> std::process::Output {
    let gen = gen_bin();
    let trap = if ignore_signal { "trap '' XFSZ;" } else { "" };
    let script = format!(
        "{trap} ulimit -f 64; exec \"$0\" --scenario scale --out \"$1\" --samples 40 --size 32 --force"
    );
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(&gen)
        .arg(dir)
        .output()
        .unwrap()
}

#[test]
fn an_interrupted_write_never_leaves_a_dataset_that_looks_complete() {
    let tmp = tempfile::tempdir().unwrap();
    let gen = gen_bin();
    for ignore_signal in [false, true] {
        let out = tmp.path().join(format!("ds-{ignore_signal}"));
        // A complete earlier dataset is being overwritten.
        let r = run(
            &gen,
            &[
                "--scenario",
                "scale",
                "--out",
                out.to_str().unwrap(),
                "--samples",
                "2",
                "--size",
                "8",
            ],
        );
        assert!(r.status.success());
        let r = gen_with_file_limit(&out, ignore_signal);
        assert!(
            !r.status.success(),
            "the 64 KiB limit must stop a 3 MB write"
        );
        let names = files(&out);
        assert!(!names.contains(&"meta.json".to_string()), "{names:?}");
        assert!(physvid_shared::read_dataset(&out).is_err());
        if ignore_signal {
            assert_eq!(r.status.code(), Some(1));
            let err = stderr(&r);
            assert!(
                err.contains("frames.npy") && err.trim().lines().count() == 1,
                "{err}"
            );
            assert!(!names.iter().any(|n| n.ends_with(".partial")), "{names:?}");
        }
    }
}

#[test]
fn help_explains_every_flag() {
    let r = run(&gen_bin(), &["--help"]);
    assert!(r.status.success());
    let help = String::from_utf8_lossy(&r.stdout);
    for flag in [
        "--scenario",
        "--out",
        "--samples",
        "--frames",
        "--size",
        "--dt",
        "--omega",
        "--zeta",
        "--seed",
        "--noise",
        "--force",
        "--threads",
    ] {
        assert!(help.contains(flag), "--help lacks {flag}");
    }
}

#[test]
fn output_matches_the_committed_fixture_byte_for_byte() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/tiny-position");
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let r = run(
        &gen_bin(),
        &[
            "--scenario",
            "position",
            "--out",
            out.to_str().unwrap(),
            "--samples",
            "4",
            "--frames",
            "6",
            "--size",
            "12",
            "--seed",
            "7",
            "--noise",
            "0.05",
            "--threads",
            "3",
        ],
    );
    assert!(r.status.success(), "{}", stderr(&r));
    for name in ["frames.npy", "meta.json", "preview.png"] {
        let want = std::fs::read(fixture.join(name)).unwrap();
        let got = std::fs::read(out.join(name)).unwrap();
        assert!(
            want == got,
            "{name} differs from fixtures/tiny-position (see fixtures/README.md)"
        );
    }
}

#[test]
fn numpy_loads_the_frames_unchanged() {
    let python = Path::new(env!("CARGO_MANIFEST_DIR")).join("../.venv/bin/python");
    if !python.exists() {
        eprintln!("skipped: no .venv/bin/python (run scripts/setup.sh)");
        return;
    }
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/tiny-position");
    let script = "import json, sys, numpy as np\n\
        a = np.load(sys.argv[1] + '/frames.npy')\n\
        m = json.load(open(sys.argv[1] + '/meta.json'))\n\
        assert a.dtype == np.dtype('<f4') and a.flags['C_CONTIGUOUS'], a.dtype\n\
        assert list(a.shape) == m['shape'] == [4, 6, 1, 12, 12], a.shape\n\
        assert np.array(m['latents']).shape == (4, 6)\n\
        print(float(a.sum()))";
    let o = Command::new(python)
        .arg("-c")
        .arg(script)
        .arg(&fixture)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let ds = physvid_shared::read_dataset(&fixture).unwrap();
    let sum: f64 = ds.frames.iter().map(|&v| v as f64).sum();
    let numpy_sum: f64 = String::from_utf8_lossy(&o.stdout).trim().parse().unwrap();
    assert!(
        (sum - numpy_sum).abs() < 1e-3 * sum.abs(),
        "{sum} vs {numpy_sum}"
    );
}

#[test]
fn delfys_scenes_write_their_model_truth_and_calibration_reproducibly() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        ("pendulum", "length", 0.90),
        ("torricelli", "k", 0.0128),
        ("sliding-block", "incline_deg", 25.0),
        ("led", "gamma", 0.92),
        ("free-fall", "g", 9.81),
    ];
    for (scenario, key, truth) in cases {
        let mut outs = Vec::new();
        for threads in ["1", "3"] {
            let out = tmp.path().join(format!("{scenario}-{threads}"));
            let o = run(
                &gen,
                &[
                    "--scenario",
                    scenario,
                    "--setting",
                    "2",
                    "--out",
                    out.to_str().unwrap(),
                    "--samples",
                    "9",
                    "--size",
                    "20",
                    "--threads",
                    threads,
                ],
            );
            assert!(o.status.success(), "{scenario}: {}", stderr(&o));
            outs.push(out);
        }
        for name in ["frames.npy", "meta.json"] {
            assert!(
                std::fs::read(outs[0].join(name)).unwrap()
                    == std::fs::read(outs[1].join(name)).unwrap(),
                "{scenario}/{name} differs between thread counts"
            );
        }
        let ds = physvid_shared::read_dataset(&outs[0]).unwrap();
        let meta = ds.meta.unwrap();
        assert_eq!(meta.model.name, scenario);
        assert!(
            (meta.model.parameters[key] - truth).abs() < 1e-12,
            "{scenario}: {key}"
        );
        assert!(meta.fps.unwrap() > 0.0 && (meta.fps.unwrap() * meta.dt - 1.0).abs() < 1e-9);
        if scenario != "led" {
            let refs = meta.calibration["reference_points"].as_array().unwrap();
            assert_eq!(refs.len(), 5, "{scenario}");
        }
        assert!(ds.frames.iter().all(|v| (0.0..=1.0).contains(v)));
        // The scene moves: the first and last frame of the first clip differ.
        let per_frame = 20 * 20;
        let last = (ds.shape[1] - 1) * per_frame;
        let change = ds.frames[..per_frame]
            .iter()
            .zip(&ds.frames[last..last + per_frame])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        assert!(
            change > 0.01,
            "{scenario} does not change over a clip ({change})"
        );
    }
}

#[test]
fn impossible_delfys_parameters_are_refused() {
    let gen = gen_bin();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let o = out.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["--scenario", "sliding-block", "--out", o, "--set", "mu=0.9"],
            "tan",
        ),
        (
            &["--scenario", "pendulum", "--out", o, "--set", "length=-1"],
            "length",
        ),
        (
            &["--scenario", "free-fall", "--out", o, "--set", "h0=0"],
            "h0",
        ),
        (
            &[
                "--scenario",
                "torricelli",
                "--out",
                o,
                "--set",
                "h_start=0.005",
            ],
            "h_start",
        ),
        (
            &["--scenario", "led", "--out", o, "--set", "tau=3"],
            "no parameter 'tau'",
        ),
        (
            &["--scenario", "led", "--out", o, "--omega", "3"],
            "--omega",
        ),
        (
            &["--scenario", "intensity", "--out", o, "--set", "k=1"],
            "--set",
        ),
        (
            &["--scenario", "led", "--out", o, "--setting", "4"],
            "--setting",
        ),
    ];
    for (args, needle) in cases {
        let r = run(&gen, args);
        let err = stderr(&r);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    assert!(!out.exists());
}
