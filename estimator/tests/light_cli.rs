//! A light that dims in place, end to end: a disc held bright for a second and then dimming
//! exponentially (an LED as its capacitor drains), encoded as a video; nothing moves, so
//! `estimate` reads the brightness of the region that changes, finds where its decay holds,
//! and trains the LED there, starting the latent from the brightness's rate.

mod util;

use util::{encode_lossless, guided_run, track_law, write_frames_of};

const FPS: u32 = 30;
/// The decay rate (1/s) and when it starts (s).
const GAMMA: f64 = 0.8;
const DIMS_AT: f64 = 1.0;

#[test]
fn a_dimming_light_is_read_by_its_brightness_and_guides_the_led() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames_of(&frames, 180, 6.0, |k| {
        let t = k as f64 / FPS as f64;
        let lit = if t < DIMS_AT {
            1.0
        } else {
            (-GAMMA * (t - DIMS_AT)).exp()
        };
        (0.1 + 0.8 * lit, 0.0)
    });
    let video = tmp.path().join("dimming.mkv");
    encode_lossless(&frames, &video, FPS);
    let (_, err, report) = guided_run(&video, &tmp.path().join("run"));
    let track = &report["track"];
    assert_eq!(track["track"]["reading"], "brightness", "{track}");
    assert_eq!(track["chosen"], "decay", "{track}");
    let law = track_law(&report, "decay");
    let first = law["first_s"].as_f64().unwrap();
    assert!(
        (0.9..=1.1).contains(&first),
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
