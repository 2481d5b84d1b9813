//! A light that dims in place, end to end: a disc held bright for a second and then dimming
//! exponentially (an LED as its capacitor drains), encoded as a video; nothing moves but, in one
//! of them, a hand crossing the picture at a steady speed before the light dims, and in another
//! the camera, shaken over a textured wall. `estimate` reads the brightness of the region that
//! changes (on frames steadied against the shake), finds where its decay holds, and trains the
//! LED there, starting the latent from the brightness's rate.

mod util;

use std::path::{Path, PathBuf};
use util::{encode_lossless, guided_run, track_law};

const FPS: u32 = 30;
const FRAMES: usize = 180;
/// The decay rate (1/s) and when it starts (s).
const GAMMA: f64 = 0.8;
const DIMS_AT: f64 = 1.0;

/// What happens beside the light.
#[derive(Clone, Copy, PartialEq)]
enum Scene {
    /// Nothing.
    Still,
    /// A hand crosses the picture first.
    Hand,
    /// The camera shakes by up to 2.5 px over a textured wall.
    Shaken,
}

/// The light at (40, 24) of an 80×60 dark picture, radius 6, bright until `DIMS_AT` and then
/// dimming; with `Scene::Hand`, a grey disc of radius 5 crossing the picture's bottom at a
/// steady speed over 0.1–0.9 s; with `Scene::Shaken`, the wall textured and the whole scene
/// moved each frame by a different shift. Each pixel's share of a disc from 4×4 samples; a
/// lossless video.
fn video(dir: &Path, scene: Scene) -> PathBuf {
    let frames = dir.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    let cover = |x: f64, y: f64, cx: f64, cy: f64, r: f64| {
        (0..16)
            .filter(|s| {
                let dx = x + (s % 4) as f64 / 4.0 + 0.125 - cx;
                let dy = y + (s / 4) as f64 / 4.0 + 0.125 - cy;
                dx * dx + dy * dy < r * r
            })
            .count() as f64
            / 16.0
    };
    for k in 0..FRAMES {
        let t = k as f64 / FPS as f64;
        let lit = if t < DIMS_AT {
            1.0
        } else {
            (-GAMMA * (t - DIMS_AT)).exp()
        };
        let at =
            (scene == Scene::Hand && (0.1..0.9).contains(&t)).then(|| 5.0 + 70.0 * (t - 0.1) / 0.8);
        let (sx, sy) = match scene {
            // A hand's shake: no period, a different shift each frame.
            Scene::Shaken => {
                let jolt = |salt: f64| ((k as f64 * 12.9898 + salt).sin() * 43758.5453).fract();
                (2.0 * jolt(0.0), 1.5 * jolt(78.233))
            }
            _ => (0.0, 0.0),
        };
        let img = image::GrayImage::from_fn(80, 60, |x, y| {
            let (u, v) = (x as f64 - sx, y as f64 - sy);
            let wall = match scene {
                Scene::Shaken => {
                    0.3 + 0.12 * (0.7 * u).sin() * (0.5 * v).cos()
                        + 0.08 * (0.23 * u + 0.31 * v).sin()
                }
                _ => 0.1,
            };
            let mut v = wall + 0.8 * lit * cover(u, v, 40.5, 24.5, 6.0);
            if let Some(hx) = at {
                let c = cover(x as f64, y as f64, hx, 50.5, 5.0);
                v = v * (1.0 - c) + 0.6 * c;
            }
            image::Luma([(v.min(1.0) * 255.0).round() as u8])
        });
        img.save(frames.join(format!("frame{}.png", k + 1)))
            .unwrap();
    }
    let video = dir.join("dimming.mkv");
    encode_lossless(&frames, &video, FPS);
    video
}

/// The run on a dimming light's video: the brightness read, its decay from `DIMS_AT` at
/// `GAMMA`, and the LED trained there from it.
fn read_by_its_brightness(scene: Scene) {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path(), scene);
    let (_, err, report) = guided_run(&v, &tmp.path().join("run"));
    let track = &report["track"];
    assert_eq!(track["track"]["reading"], "brightness", "{track}");
    assert_eq!(track["chosen"], "decay", "{track}");
    let steadied = track["track"]["steadied"].as_f64();
    match scene {
        Scene::Shaken => assert!(steadied.is_some_and(|s| s > 1.0), "{track}"),
        _ => assert!(steadied.is_none(), "{track}"),
    }
    let law = track_law(&report, "decay");
    let first = law["first_s"].as_f64().unwrap();
    // Steadied frames are resampled between pixels, and the light's edge with them: the
    // decay is found to hold a few frames later.
    let late = if scene == Scene::Shaken { 0.25 } else { 0.1 };
    assert!(
        (0.9..=DIMS_AT + late).contains(&first),
        "the decay starts at {first} s"
    );
    let g = law["values"][0]["value"].as_f64().unwrap();
    assert!((g / GAMMA - 1.0).abs() < 0.01, "the brightness's γ {g}");
    // The LED trained on that span, started from the brightness's rate.
    assert_eq!(report["model"], "led", "{err}");
    assert!(
        err.contains("the brightness of what changes in place decays over"),
        "{err}"
    );
    assert!(
        err.contains("the latent route trained the led there"),
        "{err}"
    );
    let answer = util::estimate_of(&report, "gamma");
    assert!(
        (answer / GAMMA - 1.0).abs() < 0.02,
        "the answer's γ {answer}"
    );
}

#[test]
fn a_dimming_light_is_read_by_its_brightness_and_guides_the_led() {
    read_by_its_brightness(Scene::Still);
}

/// The hand's steady crossing is a constant acceleration (of none) that holds on its track:
/// the brightness is still read, its decay guiding where nothing that moves does.
#[test]
fn a_hand_crossing_before_the_light_dims_does_not_hide_it() {
    read_by_its_brightness(Scene::Hand);
}

/// A shaken camera moves every edge of the wall: the frames are steadied before the
/// brightness is read, and its decay guides as on a still camera.
#[test]
fn a_shaken_camera_is_steadied_before_the_light_is_read() {
    read_by_its_brightness(Scene::Shaken);
}
