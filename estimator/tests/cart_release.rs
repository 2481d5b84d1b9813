//! A cart at rest, then pulled from rest along a level rail, end to end: its track's constant
//! acceleration is read from rest (the still frames before the release pin it instead of pulling
//! the parabola's vertex early), and the acceleration in metres by three readings is the
//! track's where the track measures it more precisely than the latent.

mod util;

use std::path::{Path, PathBuf};
use util::{estimate_of, gray_video, parameter, read_report, stderr, track_law, Estimate};

const FPS: u32 = 30;
const FRAMES: usize = 90;
/// The release (s), the acceleration (m/s²) and the picture's scale (px a metre).
const RELEASE: f64 = 0.5;
const A: f64 = 0.3;
const PER_METRE: f64 = 100.0;
const W: u32 = 160;
const H: u32 = 90;

/// The cart's left edge (px) at time `t`.
fn left(t: f64) -> f64 {
    20.0 + 0.5 * A * (t - RELEASE).max(0.0).powi(2) * PER_METRE
}

/// A value in [0, 1) from `k` alone: the wall's texture and the pixels' noise, the same on
/// every run.
fn hashed(k: u64) -> f64 {
    let mut x = k.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    x ^= x >> 29;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 32;
    (x >> 11) as f64 / (1u64 << 53) as f64
}

/// The frames: a wall of 4-px grey blocks, a rail, and a dark cart 16×8 px whose edges cover
/// their columns in part, ±2 grey levels of noise.
fn video(dir: &Path) -> PathBuf {
    gray_video(dir, "cart.mkv", (FRAMES, FPS), (W, H), |k, x, y| {
        let x0 = left(k as f64 / FPS as f64);
        let block = (y / 4) as u64 * 1000 + (x / 4) as u64;
        let mut v = if (48..66).contains(&y) {
            200.0
        } else {
            170.0 + 60.0 * hashed(block)
        };
        if (62..64).contains(&y) {
            v = 90.0;
        }
        if (54..62).contains(&y) {
            let x = x as f64;
            let cover = (x + 1.0 - x0).min(x0 + 16.0 - x).clamp(0.0, 1.0);
            v = v * (1.0 - cover) + 40.0 * cover;
        }
        let noise = 4.0 * (hashed((k * 100_000 + (y * W + x) as usize) as u64) - 0.5);
        (v + noise).round().clamp(0.0, 255.0) as u8
    })
}

#[test]
fn a_cart_pulled_from_rest_is_read_from_its_release() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path());
    let at = |t: f64| 0.5 * A * (t - RELEASE).powi(2);
    let readings = format!("{RELEASE}s=0,1.5s={:.5},2.0s={:.5}", at(1.5), at(2.0));
    let out = tmp.path().join("run");
    let o = Estimate::new(&v)
        .args(["--reference", &readings])
        .args(["--epochs", "20", "--threads", "1", "--seed", "1"])
        .out(&out)
        .output();
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", stderr(&o));
    let report = read_report(&out);
    assert_eq!(report["track"]["chosen"], "constant-acceleration");
    let law = track_law(&report, "constant-acceleration");
    let value = |name: &str| {
        law["values"]
            .as_array()
            .unwrap()
            .iter()
            .find(|v| v["name"] == name)
            .unwrap()["value"]
            .as_f64()
            .unwrap()
    };
    // The release where it was (a parabola through the still frames put it 0.010 s early
    // here, 0.05–0.09 s on the carts suite's), and the acceleration with it.
    let vertex = value("vertex");
    assert!(
        (vertex - RELEASE).abs() < 0.005,
        "release read at {vertex} s"
    );
    let px = value("acceleration");
    assert!((px / (A * PER_METRE) - 1.0).abs() < 0.02, "{px} px/s^2");
    // The answer the track's, within 2 % (the latent's, 20 epochs in, was 79 % high before),
    // the latent's kept beside it.
    let a = estimate_of(&report, "acceleration");
    assert!((a / A - 1.0).abs() < 0.02, "answer {a} m/s^2");
    let routes = &parameter(&report, "acceleration")["routes"];
    assert_eq!(routes["track"].as_f64(), Some(a), "{routes}");
    assert!(routes["latent"].as_f64().is_some(), "{routes}");
}
