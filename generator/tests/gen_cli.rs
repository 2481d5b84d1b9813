//! End-to-end tests of the real `gen` binary on the oscillator scenes: reproducibility across
//! thread counts, bad input, overwrite protection, crash safety, the committed fixture.

mod util;

use physvid_shared::outdir::MANIFEST;
use std::path::Path;
use std::process::Command;
use util::{bin, files, fixtures, gen, gen_scene, stderr};

#[test]
fn same_arguments_give_byte_identical_files_on_1_and_4_threads() {
    let tmp = tempfile::tempdir().unwrap();
    for scenario in ["intensity", "position", "scale"] {
        let set = |out: &Path, seed: &str| {
            gen_scene(scenario, out)
                .args(["--samples", "37", "--frames", "9", "--size", "24"])
                .args(["--noise", "0.05", "--seed", seed])
        };
        let mut outputs = Vec::new();
        for threads in ["1", "4"] {
            let out = tmp.path().join(format!("{scenario}-{threads}"));
            set(&out, "11").args(["--threads", threads]).ok();
            outputs.push(out);
        }
        assert_eq!(
            files(&outputs[0]),
            [MANIFEST, "frames.npy", "meta.json", "preview.png"]
        );
        for name in ["frames.npy", "meta.json", "preview.png"] {
            let a = std::fs::read(outputs[0].join(name)).unwrap();
            let b = std::fs::read(outputs[1].join(name)).unwrap();
            assert!(a == b, "{scenario}/{name} differs between 1 and 4 threads");
        }
        // A different seed gives different frames.
        let other = tmp.path().join(format!("{scenario}-seed12"));
        set(&other, "12").ok();
        assert_ne!(
            std::fs::read(other.join("frames.npy")).unwrap(),
            std::fs::read(outputs[0].join("frames.npy")).unwrap()
        );
    }
}

#[test]
fn written_dataset_reads_back_with_its_ground_truth() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    let o = gen_scene("position", &out)
        .args(["--samples", "5", "--frames", "6", "--size", "16"])
        .args(["--dt", "0.1", "--omega", "3", "--zeta", "0.1"])
        .ok();
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
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let scale = || gen_scene("scale", &out);
    let position = || gen_scene("position", &out);
    gen_scene("wobble", &out).bad_input("--scenario");
    scale().args(["--size", "4"]).bad_input("--size");
    scale().args(["--frames", "2"]).bad_input("--frames");
    scale().args(["--samples", "0"]).bad_input("--samples");
    for n in ["0", "100000"] {
        scale()
            .args(["--threads", n])
            .bad_input("must be from 1 to 256");
    }
    for dt in ["0", "-0.1", "inf", "NaN"] {
        scale().args(["--dt", dt]).bad_input("--dt");
    }
    position().args(["--zeta", "-0.5"]).bad_input("--zeta");
    position().args(["--omega", "30"]).bad_input("--omega");
    position().args(["--noise", "2"]).bad_input("--noise");
    scale()
        .args(["--samples", "100000", "--size", "200"])
        .bad_input("8 GiB");
    // Issue 14: flags that did not apply, misleading blame, degenerate physics.
    let scene = |name: &str, args: &[&str]| gen_scene(name, &out).args(args.to_vec());
    scene("intensity", &["--setting", "2"]).bad_input("--setting 2: intensity has no settings");
    scene("intensity", &["--size", "100000"]).bad_input("--size 100000: must be from 8 to 4096");
    scene("sliding-block", &["--set", "travel=0.001"]).bad_input("--set travel=0.001,mu=0.21");
    scene("intensity", &["--dt", "1e-300"]).bad_input("--dt 1e-300: must be from 1e-6");
    scene("intensity", &["--dt", "1e-5"]).bad_input("too little to see it move");
    scene("intensity", &["--zeta", "1e9"]).bad_input("need zeta*dt <= 2");
    scene("pendulum", &["--set", "length=1e-9"]).bad_input("below its Nyquist rate");
    scene("pendulum", &["--dt", "5"]).bad_input("--dt 5: a pendulum of length 0.45 m");
    assert!(!out.exists(), "nothing is written on bad input");
}

#[test]
fn existing_non_empty_directory_needs_force() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("notes.txt"), "keep").unwrap();
    let cmd = gen_scene("intensity", tmp.path()).args(["--samples", "3", "--size", "8"]);
    let r = cmd.output();
    assert_eq!(r.status.code(), Some(2));
    assert!(stderr(&r).contains("--force"), "{}", stderr(&r));
    cmd.arg("--force").ok();
    assert_eq!(
        files(tmp.path()),
        [
            MANIFEST,
            "frames.npy",
            "meta.json",
            "notes.txt",
            "preview.png"
        ]
    );
    assert_eq!(
        std::fs::read(tmp.path().join("notes.txt")).unwrap(),
        b"keep"
    );
}

/// Runs gen under a file-size limit so the write of frames.npy fails part-way: killed by
/// SIGXFSZ (a crash) or, with the signal ignored, an EFBIG write error (a full disk).
fn gen_with_file_limit(dir: &Path, ignore_signal: bool) -> std::process::Output {
    let trap = if ignore_signal { "trap '' XFSZ;" } else { "" };
    let script = format!(
        "{trap} ulimit -f 64; exec \"$0\" --scenario scale --out \"$1\" --samples 40 --size 32 --force"
    );
    Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(bin())
        .arg(dir)
        .output()
        .unwrap()
}

#[test]
fn an_interrupted_write_never_leaves_a_dataset_that_looks_complete() {
    let tmp = tempfile::tempdir().unwrap();
    for ignore_signal in [false, true] {
        let out = tmp.path().join(format!("ds-{ignore_signal}"));
        // A complete earlier dataset is being overwritten.
        gen_scene("scale", &out)
            .args(["--samples", "2", "--size", "8"])
            .ok();
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
    let r = gen().arg("--help").ok();
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
    let fixture = fixtures().join("tiny-position");
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("ds");
    gen_scene("position", &out)
        .args(["--samples", "4", "--frames", "6", "--size", "12"])
        .args(["--seed", "7", "--noise", "0.05", "--threads", "3"])
        .ok();
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
    if !physvid_testkit::require(
        ".venv/bin/python",
        python.exists(),
        "scripts/setup.sh makes it with numpy",
    ) {
        return;
    }
    let fixture = fixtures().join("tiny-position");
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
