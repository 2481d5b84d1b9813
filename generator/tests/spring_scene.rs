//! End-to-end tests of the real `gen` binary on the two-body spring (appendix A.5): the
//! truth it writes, reproducibility across thread counts, colour frames, refusals.

mod util;

use util::gen_scene;

#[test]
fn spring_writes_both_bodies_truth_reproducibly_in_grey_and_colour() {
    let tmp = tempfile::tempdir().unwrap();
    for (colour, channels) in [(false, 1usize), (true, 3)] {
        let mut outs = Vec::new();
        for threads in ["1", "3"] {
            let out = tmp.path().join(format!("spring-{colour}-{threads}"));
            let cmd = gen_scene("spring", &out).args(["--samples", "6", "--threads", threads]);
            let cmd = if colour { cmd.arg("--color") } else { cmd };
            cmd.ok();
            outs.push(out);
        }
        for name in ["frames.npy", "meta.json", "preview.png"] {
            assert!(
                std::fs::read(outs[0].join(name)).unwrap()
                    == std::fs::read(outs[1].join(name)).unwrap(),
                "spring (colour {colour}) {name} differs between thread counts"
            );
        }
        let ds = physvid_shared::read_dataset(&outs[0]).unwrap();
        assert_eq!(ds.shape, [6, 12, channels, 64, 64]);
        let meta = ds.meta.unwrap();
        assert_eq!(meta.model.name, "spring");
        assert_eq!(meta.model.parameters["k"], 2.0);
        assert_eq!(meta.model.parameters["rest_length"], 24.0);
        assert_eq!(meta.latent_dims, 4);
        assert!(meta.latents.iter().all(|l| l.len() == 12 * 4));
        let refs = &meta.calibration.reference_positions;
        assert!(refs.len() >= 2);
        // The reference positions are the truth at those frames.
        for r in refs {
            let at = &meta.latents[r.clip][r.frame * 4..r.frame * 4 + 4];
            assert_eq!(r.positions, at);
        }
        // The bodies stay in the frame, and the law holds: the relative vector's length
        // oscillates about the rest length.
        let lengths: Vec<f64> = meta
            .latents
            .iter()
            .flat_map(|l| l.chunks(4).map(|p| (p[2] - p[0]).hypot(p[3] - p[1])))
            .collect();
        assert!(meta
            .latents
            .iter()
            .flatten()
            .all(|&v| (0.0..64.0).contains(&v)));
        let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
        assert!((mean - 24.0).abs() < 8.0, "mean separation {mean}");
        assert!(ds.frames.iter().all(|v| (0.0..=1.0).contains(v)));
    }
}

#[test]
fn impossible_spring_settings_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let spring = || gen_scene("spring", &out);
    spring().args(["--set", "k=-1"]).bad_input("k=-1");
    spring().args(["--set", "clutter=0.5"]).bad_input("clutter");
    spring().args(["--size", "30"]).bad_input("--size");
    spring().args(["--set", "k=200"]).bad_input("Nyquist");
    spring()
        .args(["--set", "rest_length=90"])
        .bad_input("rest_length");
    spring().args(["--set", "mass=2"]).bad_input("mass");
    assert!(!out.exists());
}
