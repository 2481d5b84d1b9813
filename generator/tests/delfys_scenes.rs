//! End-to-end tests of the real `gen` binary on the Delfys75 scenes: model truth, calibration,
//! reproducibility across thread counts, impossible parameters.

mod util;

use util::gen_scene;

#[test]
fn delfys_scenes_write_their_model_truth_and_calibration_reproducibly() {
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
            gen_scene(scenario, &out)
                .args(["--setting", "2", "--samples", "9", "--size", "20"])
                .args(["--threads", threads])
                .ok();
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
            assert_eq!(meta.calibration.reference_points.len(), 5, "{scenario}");
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
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let scene = |s: &str| gen_scene(s, &out);
    scene("sliding-block")
        .args(["--set", "mu=0.9"])
        .bad_input("tan");
    scene("pendulum")
        .args(["--set", "length=-1"])
        .bad_input("length");
    scene("free-fall").args(["--set", "h0=0"]).bad_input("h0");
    scene("torricelli")
        .args(["--set", "h_start=0.005"])
        .bad_input("h_start");
    scene("led")
        .args(["--set", "tau=3"])
        .bad_input("no parameter 'tau'");
    scene("led").args(["--omega", "3"]).bad_input("--omega");
    scene("intensity").args(["--set", "k=1"]).bad_input("--set");
    scene("led").args(["--setting", "4"]).bad_input("--setting");
    assert!(!out.exists());
}
