//! A tank draining through a hole in its bottom, end to end: the brightness of what changes
//! (the column the water leaves) follows Torricelli's drain, which guides the latent route to the
//! tank alone (no choice among every model), and the tank's k in metres by three heights read
//! is the track's, from the level's empty time, where the track measures it more precisely.

mod util;

use std::path::{Path, PathBuf};
use util::{estimate_of, gray_video, parameter, read_report, stderr, Estimate};

const FPS: u32 = 5;
const FRAMES: usize = 120;
/// Torricelli's k (m^0.5/s), the starting level (m) and the picture's scale (px a metre).
const K: f64 = 0.0162;
const H0: f64 = 0.07;
const PER_METRE: f64 = 800.0;
/// The tank's bottom (row) and its columns.
const BOTTOM: f64 = 70.0;
const W: u32 = 64;
const H: u32 = 80;

/// The water's height (m) at time `t`.
fn level(t: f64) -> f64 {
    (H0.sqrt() - 0.5 * K * t).max(0.0).powi(2)
}

/// The frames: a grey wall, a light tank 24 px wide, dark water up to the level (its surface
/// covering its row in part), ±2 grey levels of noise.
fn video(dir: &Path) -> PathBuf {
    gray_video(dir, "tank.mkv", (FRAMES, FPS), (W, H), |k, x, y| {
        let surface = BOTTOM - level(k as f64 / FPS as f64) * PER_METRE;
        let mut v = 150.0;
        if (20..44).contains(&x) && (10..70).contains(&y) {
            let wet = (y as f64 + 1.0 - surface).clamp(0.0, 1.0);
            v = 210.0 * (1.0 - wet) + 60.0 * wet;
        }
        let n = ((k * 7919 + (y * W + x) as usize * 104_729) % 1000) as f64 / 1000.0;
        (v + 4.0 * (n - 0.5)).round().clamp(0.0, 255.0) as u8
    })
}

#[test]
fn a_draining_tank_guides_the_tank_and_its_k_is_the_tracks() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path());
    let readings = format!(
        "2s={:.5},10s={:.5},20s={:.5}",
        level(2.0),
        level(10.0),
        level(20.0)
    );
    let out = tmp.path().join("run");
    let o = Estimate::new(&v)
        .args(["--reference", &readings])
        .args(["--epochs", "20", "--threads", "1", "--seed", "1"])
        .out(&out)
        .output();
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", stderr(&o));
    let report = read_report(&out);
    assert_eq!(report["track"]["chosen"], "drain", "{}", stderr(&o));
    // The tank alone, not a choice among every model.
    assert_eq!(report["model"], "torricelli");
    assert!(report["model_choice"].is_null());
    let k = estimate_of(&report, "k");
    assert!((k / K - 1.0).abs() < 0.02, "k {k}");
    let routes = &parameter(&report, "k")["routes"];
    assert_eq!(routes["track"].as_f64(), Some(k), "{routes}");
    assert!(routes["latent"].as_f64().is_some(), "{routes}");
}
