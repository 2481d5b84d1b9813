//! A coloured ball as bright as the wall behind it, swung from near the horizontal: its grey
//! shows nothing that moves, its colour does (`track`'s chroma reading); the track finds the
//! swing and its g/L, and guides the latent route's pendulum there, calibrated by the track's
//! angles about the pivot.

mod util;

use std::path::{Path, PathBuf};
use util::{guided_run, track_law};

const FPS: u32 = 30;
const FRAMES: usize = 120;
/// θ'' = −(g/L) sin θ − ζ θ' from 80° at rest.
const G_OVER_L: f64 = 18.0;
const DAMPING: f64 = 0.2;
const START_DEG: f64 = 80.0;
/// The pivot and the string's length (pixels), the ball's radius.
const PIVOT: (f64, f64) = (100.0, 10.0);
const LENGTH: f64 = 90.0;
const RADIUS: f64 = 6.0;

/// 120 colour frames (200×120) of a yellow-green ball of the grey wall's brightness swinging,
/// encoded as a lossless FFV1 video (yuv444p).
fn film(dir: &Path) -> PathBuf {
    let frames = dir.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    // Luma 0.299 R + 0.587 G + 0.114 B: 152.5 for the ball, 152 for the wall.
    let (wall, ball) = ([152.0; 3], [165.0, 168.0, 40.0]);
    let angles = util::swing_angles(FRAMES, FPS, G_OVER_L, DAMPING, START_DEG);
    for (k, a) in angles.iter().enumerate() {
        let (bx, by) = (PIVOT.0 + LENGTH * a.sin(), PIVOT.1 + LENGTH * a.cos());
        let img = image::RgbImage::from_fn(200, 120, |x, y| {
            let d = (x as f64 + 0.5 - bx).hypot(y as f64 + 0.5 - by);
            let cover = (RADIUS + 0.5 - d).clamp(0.0, 1.0);
            image::Rgb(std::array::from_fn(|c| {
                (wall[c] * (1.0 - cover) + ball[c] * cover).round() as u8
            }))
        });
        img.save(frames.join(format!("frame{}.png", k + 1)))
            .unwrap();
    }
    let video = dir.join("swing.mkv");
    util::encode_ffv1(&frames, &video, FPS, "yuv444p");
    video
}

#[test]
fn a_ball_as_bright_as_its_wall_is_followed_by_its_colour_and_its_swing_guides_the_pendulum() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = film(tmp.path());
    let (_, err, report) = guided_run(&v, &tmp.path().join("run"));
    let track = &report["track"];
    assert_eq!(track["chosen"], "swing", "{track}");
    let law = track_law(&report, "swing");
    let value = |name: &str| {
        law["values"]
            .as_array()
            .unwrap()
            .iter()
            .find(|v| v["name"] == name)
            .and_then(|v| v["value"].as_f64())
            .unwrap()
    };
    let g = value("g_over_l");
    assert!((g / G_OVER_L - 1.0).abs() < 0.01, "track g/L {g}");
    assert!(value("rest").abs() < 1.0, "{law}");
    // The whole swing, seen in its colour.
    let n = track["track"]["t"].as_array().unwrap().len();
    assert!(n >= 110, "{n} samples");
    // The latent route: the pendulum on the track's span, its angle scale from the track.
    assert_eq!(report["model"], "pendulum");
    assert!(
        err.contains("the latent route trained the pendulum there")
            && err.contains("calibrated by the track's 6 angles about its pivot"),
        "{err}"
    );
    assert!(
        !err.contains("the pendulum's angle scale was learned, not calibrated"),
        "{err}"
    );
}
