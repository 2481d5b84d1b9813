//! A shaken camera, end to end: a dark disc oscillating on a textured wall, filmed by a hand
//! that shakes the whole picture by a few pixels a frame. Read as shot, every edge of the wall
//! moves and no law holds on anything followed; `estimate` steadies the frames against the
//! shake, follows the disc on them, and its oscillation guides the oscillator, whose latent
//! reads the frames steadied by the same shifts.

mod util;

use std::path::{Path, PathBuf};
use util::{encode_lossless, guided_run, track_law};

const FPS: u32 = 30;
const FRAMES: usize = 240;
/// The oscillation: its angular frequency (1/s) and damping γ1 (1/s).
const OMEGA: f64 = 5.0;
const GAMMA1: f64 = 0.1;

/// The camera's shift at frame `k` (pixels): a hand's shake, a slow wander and a jolt each
/// frame, with no period.
fn shake(k: usize) -> (f64, f64) {
    let jolt = |salt: f64| ((k as f64 * 12.9898 + salt).sin() * 43758.5453).fract();
    let wander = |salt: f64| (k as f64 * 0.37 + salt).sin() + 0.6 * (k as f64 * 0.23 + salt).cos();
    (
        2.0 * wander(0.0) + 1.0 * jolt(0.0),
        2.0 * wander(1.7) + 1.0 * jolt(78.233),
    )
}

/// The disc (radius 6, dark) at (80, 60 + 25 e^(−γ1 t/2) cos ωt) of a 160×120 wall textured
/// by a few sines of no common period, everything moved by `shake`; each pixel's share of the
/// disc from 4×4 samples; a lossless video.
fn video(dir: &Path) -> PathBuf {
    let frames = dir.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    for k in 0..FRAMES {
        let t = k as f64 / FPS as f64;
        let y = 60.0 + 25.0 * (-GAMMA1 * t / 2.0).exp() * (OMEGA * t).cos();
        let (sx, sy) = shake(k);
        let img = image::GrayImage::from_fn(160, 120, |x, yy| {
            let (u, v) = (x as f64 - sx, yy as f64 - sy);
            let wall = 0.5
                + 0.15 * (0.21 * u + 0.5).sin() * (0.13 * v).cos()
                + 0.1 * (0.07 * u + 0.17 * v).sin()
                + 0.08 * (0.29 * u - 0.11 * v + 1.3).cos() * (0.05 * v).sin();
            let cover = (0..16)
                .filter(|s| {
                    let dx = u + (s % 4) as f64 / 4.0 + 0.125 - 80.5;
                    let dy = v + (s / 4) as f64 / 4.0 + 0.125 - (y + 0.5);
                    dx * dx + dy * dy < 36.0
                })
                .count() as f64
                / 16.0;
            let value = wall * (1.0 - cover) + 0.05 * cover;
            image::Luma([(value * 255.0).round() as u8])
        });
        img.save(frames.join(format!("frame{}.png", k + 1)))
            .unwrap();
    }
    let video = dir.join("shaken.mkv");
    encode_lossless(&frames, &video, FPS);
    video
}

#[test]
fn a_shaken_camera_is_steadied_and_the_oscillation_guides() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path());
    let (o, err, report) = guided_run(&v, &tmp.path().join("run"));
    let out = String::from_utf8_lossy(&o.stdout);
    let track = &report["track"];
    assert_eq!(track["chosen"], "oscillation", "{track}");
    let steadied = track["track"]["steadied"].as_f64();
    assert!(steadied.is_some_and(|s| s > 2.0), "{track}");
    let law = track_law(&report, "oscillation");
    let g0 = law["values"][0]["value"].as_f64().unwrap();
    let truth = OMEGA * OMEGA + GAMMA1 * GAMMA1 / 4.0;
    assert!((g0 / truth - 1.0).abs() < 0.01, "the track's γ0 {g0}");
    assert_eq!(report["model"], "damped-oscillator", "{err}");
    // The track's line says it was read on steadied frames.
    assert!(
        out.contains("on frames steadied against the camera's shake"),
        "{out}"
    );
    let answer = util::estimate_of(&report, "gamma0");
    assert!(
        (answer / truth - 1.0).abs() < 0.02,
        "the answer's γ0 {answer}"
    );
    // The latent route read the frames steadied as the track did, and its own values are
    // right: on the frames as shot it gave γ0 +0.36 % and γ1 −27 % (0.0729), on these 0.004 %
    // and +0.2 %.
    let warnings = report["warnings"].to_string();
    assert!(
        warnings.contains("the latent route read each frame moved back"),
        "{warnings}"
    );
    let latent = |name: &str| util::parameter(&report, name)["routes"]["latent"].as_f64();
    let g0 = latent("gamma0").unwrap();
    assert!((g0 / truth - 1.0).abs() < 0.002, "the latent's γ0 {g0}");
    let g1 = latent("gamma1").unwrap();
    assert!((g1 / GAMMA1 - 1.0).abs() < 0.1, "the latent's γ1 {g1}");
}
