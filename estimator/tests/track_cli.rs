//! The second route end to end: a disc dragged about by a "hand" for two seconds and then let go
//! to oscillate, encoded as a video; `estimate` follows it, finds where the oscillation holds,
//! trains the latent there as an independent measurement, and judges the two routes against each
//! other.

mod util;

use std::path::{Path, PathBuf};
use util::{
    encode_lossless, guided_run, read_report, stderr, stdout, track_law, write_frames_of, Estimate,
};

const FPS: u32 = 30;
/// The let-go, in frames and seconds.
const RELEASE: usize = 60;
/// The oscillation: ω = 2π (a period of 1 s), ζ = 0.05.
const OMEGA: f64 = std::f64::consts::TAU;
const ZETA: f64 = 0.05;

/// The disc's shift right of the centre (pixels) at frame k: dragged from 0 to 8 px with a
/// wobble no law here explains, then let go.
fn shift(k: usize) -> f64 {
    let t = k as f64 / FPS as f64;
    if k < RELEASE {
        8.0 * (k as f64 / RELEASE as f64).powi(2) + 1.2 * (7.3 * t).sin() * (1.7 * t).cos()
    } else {
        let s = t - RELEASE as f64 / FPS as f64;
        let at_release = 8.0 + 1.2 * (7.3 * 2.0f64).sin() * (1.7 * 2.0f64).cos();
        at_release * (-ZETA * s).exp() * (OMEGA * s).cos()
    }
}

fn video(dir: &Path) -> PathBuf {
    let frames = dir.join("frames");
    write_frames_of(&frames, 240, 4.0, |k| (0.9, shift(k)));
    let video = dir.join("released.mkv");
    encode_lossless(&frames, &video, FPS);
    video
}

#[test]
fn the_track_finds_the_free_oscillation_and_guides_the_latent_there() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path());
    let (o, err, report) = guided_run(&v, &tmp.path().join("run"));
    let track = &report["track"];
    assert_eq!(track["chosen"], "oscillation", "{track}");
    let law = track_law(&report, "oscillation");
    let first = law["first_s"].as_f64().unwrap();
    assert!((1.9..=2.3).contains(&first), "the span starts at {first} s");
    let g0 = law["values"][0]["value"].as_f64().unwrap();
    let truth = OMEGA * OMEGA + ZETA * ZETA;
    assert!(
        (g0 / truth - 1.0).abs() < 0.01,
        "track γ0 {g0} against {truth}"
    );
    // One position a frame it was seen, with its time and quality.
    let n = track["track"]["t"].as_array().unwrap().len();
    assert!(n >= 200, "{n} samples");
    assert_eq!(track["track"]["quality"].as_array().unwrap().len(), n);
    // The latent trained the oscillator on that span alone (no model choice).
    assert_eq!(report["model"], "damped-oscillator");
    assert!(
        err.contains("the latent route trained the damped-oscillator there"),
        "{err}"
    );
    // Started from the track's answer alone: the one start is the track's γ0 (no start read
    // off the frames beside it), and no retry at half the frequency.
    assert!(
        err.contains("started from the track's answer alone"),
        "{err}"
    );
    let starts = report["starts"].as_array().unwrap();
    assert_eq!(starts.len(), 1, "{starts:?}");
    assert_eq!(
        starts[0]["initial"][0].as_f64(),
        Some(g0),
        "{starts:?} against the track's {g0}"
    );
    assert!(
        report["config"]["single_start"].as_bool().unwrap(),
        "{report}"
    );
    assert!(report["model_choice"].is_null());
    // The answer: the track's, with its error, the latent's beside it; where they disagree the
    // routes check says so.
    let p = &report["parameters"][0];
    assert_eq!(p["name"], "gamma0");
    assert_eq!(p["estimate"].as_f64().unwrap(), g0, "{report}");
    let disagree = report["verdict"]["reasons"]
        .as_array()
        .unwrap()
        .iter()
        .any(|r| {
            r["check"] == "routes"
                && r["detail"]
                    .as_str()
                    .is_some_and(|d| d.contains("the latent's gamma0 is"))
        });
    let r = &p["routes"];
    let f = |k: &str| r[k].as_f64().unwrap();
    assert_eq!(f("track"), g0, "{r}");
    assert_eq!(p["standard_error"].as_f64(), Some(f("track_error")), "{r}");
    assert!(stdout(&o).contains("gamma0: the track's"), "{}", stdout(&o));
    if r["agree"] == true {
        assert!(!disagree, "{report}");
        assert!(stdout(&o).contains("agrees with it"), "{}", stdout(&o));
    } else {
        assert!(disagree, "{report}");
    }
    // The track's law held against the same frames as the latent (`guide::followed`): the
    // disc alone moves, so its law explains most of what changes.
    let track_share = report["evidence"]["track_fold"]["explained_share"].as_f64();
    assert!(
        track_share.is_some_and(|e| e > 0.5),
        "{}",
        report["evidence"]
    );
}

#[test]
fn a_law_that_does_not_oscillate_against_an_oscillating_track_is_doubtful() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = video(tmp.path());
    let out = tmp.path().join("led");
    let o = Estimate::new(&v)
        .args(["--model", "led", "--epochs", "5", "--threads", "1"])
        .out(&out)
        .output();
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", stderr(&o));
    let report = read_report(&out);
    let reasons = report["verdict"]["reasons"].as_array().unwrap();
    let routes = reasons
        .iter()
        .find(|r| r["check"] == "routes")
        .unwrap_or_else(|| panic!("no routes reason: {reasons:?}"));
    assert_ne!(routes["grade"], "ok");
    assert!(routes["detail"].as_str().unwrap().contains("led"));
}
