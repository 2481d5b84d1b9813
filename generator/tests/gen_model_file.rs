//! End-to-end tests of `gen --model FILE.toml`: a model file's system drawn on the disc scenes,
//! reproducible, with its map and reference frames in meta.json; bad files and flags refused.

mod util;

use std::path::{Path, PathBuf};
use util::gen_scene;

fn example(name: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../examples")
        .join(name);
    p.to_str().expect("UTF-8 path").to_string()
}

fn duffing(scenario: &str, out: &Path) -> physvid_testkit::TestCommand {
    duffing_set(scenario, out, "a=4,b=1,c=0.08")
}

fn duffing_set(scenario: &str, out: &Path, set: &str) -> physvid_testkit::TestCommand {
    gen_scene(scenario, out)
        .args(["--model", &example("duffing.toml"), "--set", set])
        .args(["--samples", "12", "--frames", "15", "--size", "16"])
}

#[test]
fn a_model_file_renders_reproducibly_with_its_truth_map_and_reference_frames() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    duffing("position", &a).args(["--threads", "1"]).ok();
    duffing("position", &b).args(["--threads", "3"]).ok();
    for name in ["frames.npy", "meta.json"] {
        assert!(
            std::fs::read(a.join(name)).unwrap() == std::fs::read(b.join(name)).unwrap(),
            "{name}"
        );
    }
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("meta.json")).unwrap()).unwrap();
    assert_eq!(meta["model"]["name"], "duffing");
    assert_eq!(meta["scenario"], "position");
    assert_eq!(meta["model"]["parameters"]["c"], 0.08);
    assert!(meta["latent_mapping"]
        .as_str()
        .unwrap()
        .contains("z = (x - "));
    // The map puts every frame's z in [-1, 1], reaching both ends.
    let z: Vec<f64> = meta["latents"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()))
        .collect();
    let (lo, hi) = z
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(
        (lo + 1.0).abs() < 1e-9 && (hi - 1.0).abs() < 1e-9,
        "{lo} {hi}"
    );
    assert_eq!(
        meta["calibration"]["reference_points"]
            .as_array()
            .unwrap()
            .len(),
        5
    );
    // The initial state of each clip is recorded, within the file's ranges.
    let x0 = meta["samples"][0]["x"].as_f64().unwrap();
    assert!((0.5..1.0).contains(&x0), "{x0}");
}

#[test]
fn bad_model_files_and_flags_are_refused_in_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let bad = tmp.path().join("bad.toml");
    let text = std::fs::read_to_string(example("duffing.toml")).unwrap();
    std::fs::write(&bad, text.replace("- c*v\"", "- c*w\"")).unwrap();
    let bad = bad.to_str().unwrap();
    gen_scene("position", &out)
        .args(["--model", bad])
        .bad_input("--model");
    gen_scene("position", &out)
        .args(["--model", bad])
        .bad_input("state.v: column 18: unknown name 'w'");
    duffing("pendulum", &out).bad_input("--scenario pendulum: a model file is drawn on intensity");
    duffing("position", &out)
        .args(["--omega", "2"])
        .bad_input("--omega");
    duffing_set("position", &out, "q=1").bad_input("has no parameter 'q'");
    duffing_set("position", &out, "a=4,b=-10,c=0.08").bad_input("diverges");
    duffing_set("position", &out, "a=-4").bad_input("--set a=-4: outside the file's bounds");
    let no_range = tmp.path().join("no-range.toml");
    std::fs::write(&no_range, text.replace("v = [-1.0, 1.0]\n", "")).unwrap();
    gen_scene("position", &out)
        .args(["--model", no_range.to_str().unwrap()])
        .bad_input("initial.v: gen needs a range");
    assert!(!out.exists(), "nothing is written on bad input");
}
