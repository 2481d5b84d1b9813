//! The track read from a picture whose sides the 320-px frames do not divide evenly (360×200,
//! read at 320×178): a thin rod and bob followed through the bottom of its swing, where the
//! blobs' opening breaks the rod into pieces, and a disc's positions put back in the
//! picture's pixels across and down each by its own scale. The library's `track::follow_file`
//! alone: no latent is trained.

mod util;

use estimator::track::{follow_file, laws::TrackLaw, Reading, TrackRoute};
use std::path::{Path, PathBuf};

const FPS: u32 = 30;
const SIZE: (u32, u32) = (360, 200);

/// Each frame's picture (grey levels, `SIZE`) of `ink` (how much of each pixel the object
/// covers, 0–1) over a plain wall, as a lossless grey video `dir`/NAME.mkv.
fn film(dir: &Path, name: &str, frames: usize, ink: impl Fn(usize, f64, f64) -> f64) -> PathBuf {
    let png = dir.join(name);
    std::fs::create_dir_all(&png).unwrap();
    for k in 0..frames {
        let img = image::GrayImage::from_fn(SIZE.0, SIZE.1, |x, y| {
            let cover = ink(k, x as f64 + 0.5, y as f64 + 0.5).clamp(0.0, 1.0);
            image::Luma([(180.0 * (1.0 - cover) + 40.0 * cover).round() as u8])
        });
        img.save(png.join(format!("frame{}.png", k + 1))).unwrap();
    }
    let video = dir.join(format!("{name}.mkv"));
    util::encode_lossless(&png, &video, FPS);
    video
}

/// How much of the pixel at (`x`, `y`) a disc of `radius` at `c` covers.
fn disc(x: f64, y: f64, c: (f64, f64), radius: f64) -> f64 {
    radius + 0.5 - (x - c.0).hypot(y - c.1)
}

fn follow(video: &Path) -> TrackRoute {
    follow_file(video, (None, None), None)
        .unwrap()
        .expect("a thing to follow")
}

/// A bob (9 px) on a rod 1.5 px wide from a pivot at (180, 16), 150 px long, swinging 28°
/// for 4 s: the opening keeps the rod at its tilts near the ends of the swing and breaks it
/// into pieces near the bottom, where the bob's blob alone is half the usual size; the rod's
/// region is whole throughout, and the rod's reading has every frame, not the ends alone.
#[test]
fn a_thin_rod_is_read_through_the_bottom_of_its_swing() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let (n, g_over_l) = (120, 10.0);
    let theta = util::swing_angles(n, FPS, g_over_l, 0.01, 28.0);
    let pivot = (180.0, 16.0);
    let video = film(tmp.path(), "swing", n, |k, x, y| {
        let (s, c) = theta[k].sin_cos();
        let bob = (pivot.0 + 150.0 * s, pivot.1 + 150.0 * c);
        // The rod's cover: within 0.75 px of the segment from the pivot to the bob, at 0.7.
        let u = ((x - pivot.0) * s + (y - pivot.1) * c).clamp(0.0, 150.0);
        let off = (x - pivot.0 - u * s).hypot(y - pivot.1 - u * c);
        disc(x, y, bob, 9.0).max(0.7 * (1.25 - off).clamp(0.0, 1.0))
    });
    let route = follow(&video);
    assert_eq!(route.track.reading, Reading::Rod, "{}", route.line());
    let samples = route.track.t.len();
    assert!(samples >= 114, "{samples} of {n} frames: {}", route.line());
    assert_eq!(route.chosen, Some(TrackLaw::Swing), "{}", route.line());
    let g = route.chosen_span().unwrap().rate().unwrap().value;
    assert!((g / g_over_l - 1.0).abs() < 0.003, "{}", route.line());
}

/// A disc (8 px) falling from rest along a slant from (60, 20) to (300, 180) in 2 s: each
/// sample of its track is where it was drawn, in the picture's pixels, to a twentieth of a
/// pixel (past an offset the same in every frame). One scale for both sides (the long side's,
/// 360/320) would put it 0.2 px lower at the bottom than at the top, since 178 rows stand for
/// 200.
#[test]
fn positions_are_in_the_picture_s_pixels_across_and_down() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let n = 61;
    let at = |k: usize| {
        let s = (k as f64 / (n - 1) as f64).powi(2);
        (60.0 + 240.0 * s, 20.0 + 160.0 * s)
    };
    let video = film(tmp.path(), "fall", n, |k, x, y| disc(x, y, at(k), 8.0));
    let route = follow(&video);
    let track = &route.track;
    assert!(track.t.len() >= 40, "{}", route.line());
    // Each sample's offset from where the disc was drawn; a reading by a patch's matches is
    // off by the same amount in every frame (its reference point is the patch's, not the
    // centroid), which moves nothing a law reads.
    let off: Vec<(usize, f64, f64)> = track
        .t
        .iter()
        .zip(&track.x)
        .zip(&track.y)
        .map(|((t, x), y)| {
            let k = (t * FPS as f64).round() as usize;
            (k, x - at(k).0, y - at(k).1)
        })
        .collect();
    let mean = |f: fn(&(usize, f64, f64)) -> f64| off.iter().map(f).sum::<f64>() / off.len() as f64;
    let (mx, my) = (mean(|o| o.1), mean(|o| o.2));
    for (k, dx, dy) in &off {
        assert!(
            (dx - mx).abs() < 0.05 && (dy - my).abs() < 0.05,
            "frame {k}: off by ({dx:.3}, {dy:.3}), on the whole ({mx:.3}, {my:.3}) for {:?}: {}",
            at(*k),
            route.line()
        );
    }
}
