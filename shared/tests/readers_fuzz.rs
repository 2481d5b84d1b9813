//! Property tests of the two readers every input goes through, `read_npy` and `read_dataset`
//! (meta.json): random headers and shapes, byte flips, truncations and JSON values of the wrong
//! kind or size never panic, and every refusal is one line that names the file.

use physvid_shared::meta::{GeneratorInfo, FORMAT_NAME, FORMAT_VERSION};
use physvid_shared::npy::{read_npy, write_npy};
use physvid_shared::{
    read_dataset, write_dataset, Calibration, DatasetMeta, ModelSpec, ReferencePoint, SampleTruth,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::path::Path;

const SHAPE: [usize; 5] = [2, 3, 1, 4, 4];

fn frames() -> Vec<f32> {
    (0..96).map(|i| i as f32 / 96.0).collect()
}

/// A valid `.npy` of SHAPE.
fn valid_npy() -> Vec<u8> {
    let mut bytes = Vec::new();
    write_npy(&mut bytes, &SHAPE, &frames()).unwrap();
    bytes
}

/// A valid meta.json for SHAPE, with calibration and clip start times to damage.
fn valid_meta() -> DatasetMeta {
    DatasetMeta {
        format: FORMAT_NAME.into(),
        format_version: FORMAT_VERSION,
        generator: GeneratorInfo {
            name: "fuzz".into(),
            version: "0".into(),
        },
        scenario: "intensity".into(),
        model: ModelSpec {
            name: "damped-oscillator".into(),
            parameters: [("gamma0".to_string(), 4.0)].into_iter().collect(),
            file: None,
        },
        dt: 0.2,
        shape: SHAPE,
        seed: 0,
        noise: 0.0,
        latent_mapping: String::new(),
        calibration: Calibration {
            reference_points: vec![ReferencePoint {
                clip: 0,
                frame: 1,
                value: 0.5,
            }],
            ..Default::default()
        },
        fps: None,
        clip_start_times: Some(vec![0.0, 1.0]),
        sampling: String::new(),
        samples: vec![SampleTruth::from_pairs([("amplitude", 1.0)]); 2],
        latent_dims: 1,
        latents: vec![vec![0.0; 3]; 2],
        perturbations: Vec::new(),
    }
}

/// A valid dataset in `dir/ds`; returns its path.
fn valid_dataset(dir: &Path) -> std::path::PathBuf {
    let ds = dir.join("ds");
    write_dataset(&ds, &frames(), &valid_meta(), b"png", false).unwrap();
    ds
}

/// The refusal contract: one non-empty line that names `file`.
fn one_line_naming(message: &str, file: &str) -> Result<(), TestCaseError> {
    prop_assert!(!message.trim().is_empty());
    prop_assert!(!message.contains('\n'), "{message}");
    prop_assert!(message.contains(file), "{message}");
    Ok(())
}

/// Damage: byte overwrites at random places, then an optional cut.
fn damage() -> impl Strategy<Value = (Vec<(usize, u8)>, Option<usize>)> {
    (
        prop::collection::vec((any::<usize>(), any::<u8>()), 0..6),
        prop::option::of(any::<usize>()),
    )
}

fn apply(mut bytes: Vec<u8>, flips: &[(usize, u8)], cut: Option<usize>) -> Vec<u8> {
    for &(at, b) in flips {
        let n = bytes.len();
        bytes[at % n] = b;
    }
    if let Some(c) = cut {
        bytes.truncate(c % (bytes.len() + 1));
    }
    bytes
}

/// JSON values of every kind, with extreme numbers.
fn json_value() -> impl Strategy<Value = serde_json::Value> {
    prop_oneof![
        Just(serde_json::Value::Null),
        any::<bool>().prop_map(serde_json::Value::from),
        prop_oneof![
            Just(0.0),
            Just(-1.0),
            Just(1e300),
            Just(-1e-300),
            Just(f64::MAX),
            any::<f64>().prop_filter("JSON numbers are finite", |v| v.is_finite())
        ]
        .prop_map(serde_json::Value::from),
        any::<i64>().prop_map(serde_json::Value::from),
        "[a-z ]{0,8}".prop_map(serde_json::Value::from),
        Just(serde_json::json!([])),
        Just(serde_json::json!([1.0, -2.0])),
        Just(serde_json::json!({})),
    ]
}

/// JSON pointers of every value under `v`.
fn collect_paths(v: &serde_json::Value, at: String, out: &mut Vec<String>) {
    let children: Vec<(String, &serde_json::Value)> = match v {
        serde_json::Value::Object(m) => m.iter().map(|(k, x)| (k.clone(), x)).collect(),
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .map(|(i, x)| (i.to_string(), x))
            .collect(),
        _ => Vec::new(),
    };
    for (key, x) in children {
        let p = format!("{at}/{key}");
        out.push(p.clone());
        collect_paths(x, p, out);
    }
}

proptest! {
    // Seeded (the same cases on every run) and never writing into the source tree.
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: RngSeed::Fixed(14),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn npy_reader_refuses_damage_in_one_line((flips, cut) in damage()) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("frames.npy");
        std::fs::write(&path, apply(valid_npy(), &flips, cut)).unwrap();
        if let Err(e) = read_npy(&path) {
            one_line_naming(&e.to_string(), "frames.npy")?;
        }
    }

    #[test]
    fn npy_reader_refuses_any_header_in_one_line(
        descr in prop_oneof![Just("<f4".to_string()), "[<>=|]?[a-z][0-9]{0,2}"],
        order in prop_oneof![Just("False".to_string()), Just("True".to_string()), "[A-Za-z0-9]{0,5}"],
        shape in prop::collection::vec(
            prop_oneof![Just("0".to_string()), Just("-3".to_string()), "[0-9]{1,22}", "[a-z]{1,3}"],
            0..7,
        ),
        extra in 0usize..400,
    ) {
        let dict = format!(
            "{{'descr': '{descr}', 'fortran_order': {order}, 'shape': ({}), }}",
            shape.join(", ")
        );
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend_from_slice(&(dict.len() as u16).to_le_bytes());
        bytes.extend_from_slice(dict.as_bytes());
        bytes.extend(std::iter::repeat_n(0u8, extra));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.npy");
        std::fs::write(&path, bytes).unwrap();
        if let Err(e) = read_npy(&path) {
            one_line_naming(&e.to_string(), "x.npy")?;
        }
    }

    #[test]
    fn meta_reader_refuses_damaged_text_in_one_line((flips, cut) in damage()) {
        let dir = tempfile::tempdir().unwrap();
        let ds = valid_dataset(dir.path());
        let meta = ds.join("meta.json");
        std::fs::write(&meta, apply(std::fs::read(&meta).unwrap(), &flips, cut)).unwrap();
        if let Err(e) = read_dataset(&ds) {
            one_line_naming(&e.to_string(), "meta.json")?;
        }
    }

    #[test]
    fn meta_reader_refuses_wrong_values_in_one_line(
        pick in any::<prop::sample::Index>(),
        value in json_value(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let ds = valid_dataset(dir.path());
        let meta = ds.join("meta.json");
        let mut json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&meta).unwrap()).unwrap();
        let mut paths = Vec::new();
        collect_paths(&json, String::new(), &mut paths);
        let at = pick.get(&paths).clone();
        *json.pointer_mut(&at).unwrap() = value;
        std::fs::write(&meta, serde_json::to_string(&json).unwrap()).unwrap();
        if let Err(e) = read_dataset(&ds) {
            one_line_naming(&e.to_string(), "meta.json")?;
        }
    }
}
