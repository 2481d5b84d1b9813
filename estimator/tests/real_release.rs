//! Where the free motion starts, on a recording made here (a disc swinging, held by an "arm"
//! for its first seconds) and on recordings nobody here made (`../shared/real-videos`,
//! skipped visibly where that folder is absent): a spring pulled down by a hand and let go, a
//! spring held and steadied by a hand for three seconds, and a pipe already rolling in the
//! first frame. Each was misread before (an LED's decay, a pendulum, an acceleration 11 %
//! high), with nothing but the file and the readings its README gives.

mod util;

use std::path::Path;
use util::{
    encode_lossless, estimate_of, need_ffmpeg, read_report, real_video, stderr, track_law, Estimate,
};

fn estimate(args: &[&str], out: &Path) -> (serde_json::Value, String) {
    let o = Estimate::bare().args(args).out(out).estimated();
    (read_report(out), stderr(&o))
}

/// The chosen model's rate of an oscillation: γ0, or g/L for a pendulum.
fn rate(r: &serde_json::Value) -> f64 {
    match r["model"].as_str().unwrap() {
        "pendulum" => estimate_of(r, "g_over_l"),
        _ => estimate_of(r, "gamma0"),
    }
}

#[test]
fn an_arm_that_holds_the_object_at_the_start_is_left_out() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    // 10 fps: a bright disc held near the top of its swing by a dark bar from the left edge
    // for 4 s (the hand steadying it: a pixel or two either way), then let go:
    // y = 30 + 8·cos(2 (t − 4)) e^(−0.05 (t − 4)).
    for k in 0..240 {
        let t = k as f64 / 10.0;
        let y = 30.0
            + if t < 4.0 {
                8.0 + 1.5 * (k as f64 * 1.3).sin()
            } else {
                8.0 * (2.0 * (t - 4.0)).cos() * (-0.05 * (t - 4.0)).exp()
            };
        let img = image::GrayImage::from_fn(80, 60, |c, r| {
            let (dx, dy) = (c as f64 - 40.0, r as f64 - y);
            let v = if dx * dx + dy * dy < 16.0 {
                230
            } else if t < 4.0 && c < 38 && (r as f64 - y).abs() < 5.0 {
                40
            } else {
                140 + ((c * 7 + r * 13) % 5) as u8
            };
            image::Luma([v])
        });
        img.save(frames.join(format!("frame{}.png", k + 1)))
            .unwrap();
    }
    let video = tmp.path().join("held.mkv");
    encode_lossless(&frames, &video, 10);
    let (r, err) = estimate(
        &[video.to_str().unwrap(), "--model", "damped-oscillator"],
        &tmp.path().join("run"),
    );
    let start = r["recording"]["start"].as_f64().unwrap_or(0.0);
    assert!((4.0..4.6).contains(&start), "kept from {start} s: {err}");
    let g0 = estimate_of(&r, "gamma0");
    assert!((g0 / 4.0025 - 1.0).abs() < 0.02, "γ0 {g0}: {err}");
}

/// The track's γ0 (report.json `track`, its chosen law's).
fn track_rate(r: &serde_json::Value) -> f64 {
    let law = track_law(r, r["track"]["chosen"].as_str().unwrap_or("none"));
    let v = law["values"].as_array().unwrap();
    v.iter().find(|v| v["name"] == "gamma0").unwrap()["value"]
        .as_f64()
        .unwrap()
}

#[test]
fn a_spring_pulled_down_and_let_go_by_hand_is_read_from_its_release() {
    let Some(video) = real_video("spring-k705.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let (r, err) = estimate(&[video.to_str().unwrap()], &tmp.path().join("run"));
    // The hand lets go in the first frames: the track's oscillation holds from there on (from
    // 1.43 s within its noise), and the latent route is trained on that span, framed on the
    // object's path.
    let start = r["recording"]["start"].as_f64().unwrap_or(0.0);
    assert!((0.2..2.0).contains(&start), "kept from {start} s: {err}");
    assert!(err.contains("the object's track oscillates over"), "{err}");
    assert_eq!(
        r["recording"]["framing"], "the object's path, from its track",
        "{err}"
    );
    // The period measured by tracking the mass, 1.051 s, gives γ0 = 35.7 s⁻²: the track to
    // 0.5 %, the latent to 2 %.
    let g0 = track_rate(&r);
    assert!((g0 / 35.7 - 1.0).abs() < 0.005, "track's γ0 {g0}: {err}");
    let g0 = rate(&r);
    assert!(
        (g0 / 35.7 - 1.0).abs() < 0.02,
        "{}: {g0}: {err}",
        r["model"]
    );
    // Graded ok: the latent's γ0 refitted on the first and the second half of the clips (36.3
    // and 35.4) differ by more than five standard errors, but the track's own halves agree
    // (35.71 and 35.74) and its whole γ0 is the latent's: the law holds alike, read with no
    // encoder, so the halves' gap is the encoder's and not held against the answer.
    let halves = &track_law(&r, "oscillation")["halves"];
    assert_eq!(halves.as_array().map(Vec::len), Some(2), "{err}");
    assert_eq!(r["verdict"]["grade"], "ok", "{}", r["verdict"]);
}

#[test]
fn a_spring_held_by_hand_is_read_once_the_hand_has_left() {
    let Some(video) = real_video("spring-m515-hand.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let (r, err) = estimate(&[video.to_str().unwrap()], &tmp.path().join("run"));
    // The hand lets go at about 2.4 s; the span kept is where the track's oscillation
    // holds within its noise: after the hand, and at least three periods (0.54 s each) long.
    let start = r["recording"]["start"].as_f64().unwrap_or(0.0);
    let end = r["recording"]["end"].as_f64().unwrap_or(0.0);
    assert!((2.3..6.5).contains(&start), "kept from {start} s: {err}");
    assert!(end - start > 3.0 * 0.54, "kept {start}–{end} s: {err}");
    // The track, its figure and its section of the page.
    let run = tmp.path().join("run");
    assert!(run.join("track.png").exists(), "track.png: {err}");
    let page = std::fs::read_to_string(run.join("report.html")).unwrap();
    assert!(page.contains("id=\"track-line\""), "report.html");
    // The tracked period, 0.537–0.542 s, gives γ0 = 134.4–136.9 s⁻²: the track within it (to
    // 0.5 %), the latent (started from the track's answer) within 2 % of the period's middle,
    // 135.6, and of the track's answer; the routes' reason given exactly where the two lie
    // more than three joint standard errors apart (from its own starts the latent's 132.9
    // ± 0.4 lay 3.7 of them from the track's 134.4 ± 0.2, 2.0 % low, and was graded ok). Not
    // unreliable (doubtful at present: γ1 0.02 ± 0.09, the track's 0.18 ± 0.01).
    let g0 = track_rate(&r);
    assert!(
        (134.4 * 0.995..136.9 * 1.005).contains(&g0),
        "track's γ0 {g0}: {err}"
    );
    let latent = rate(&r);
    assert!(
        (134.4 * 0.98..136.9 * 1.02).contains(&latent) && (latent / g0 - 1.0).abs() < 0.02,
        "{}: {latent}: {err}",
        r["model"]
    );
    let chosen = r["track"]["chosen"].as_str().unwrap_or("none");
    let track_error = track_law(&r, chosen)["values"][0]["error"]
        .as_f64()
        .unwrap();
    let latent_error = r["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "gamma0")
        .unwrap()["standard_error"]
        .as_f64()
        .unwrap();
    let apart = (latent - g0).abs() > 3.0 * latent_error.hypot(track_error);
    let reasons = r["verdict"]["reasons"].as_array().unwrap();
    let routes = reasons.iter().find(|x| x["check"] == "routes");
    assert_eq!(routes.is_some(), apart, "{}", r["verdict"]);
    assert!((latent / 135.6 - 1.0).abs() < 0.02, "{latent}: {err}");
    assert_ne!(r["verdict"]["grade"], "unreliable", "{}", r["verdict"]);
}

#[test]
fn a_pipe_already_rolling_in_the_first_frame_is_released_before_it() {
    let Some(video) = real_video("incline-roll10.avi") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // The README's readings: the tilt, and the distance rolled from the release at three times.
    let (r, err) = estimate(
        &[
            video.to_str().unwrap(),
            "--incline-deg",
            "10.3",
            "--reference",
            "0.30s=0.076,0.80s=0.360,1.30s=0.855",
        ],
        &tmp.path().join("run"),
    );
    assert_eq!(r["model"], "sliding-block", "{err}");
    // Released about 0.12 s before the first frame (4 frames at 29.97 fps).
    let release = r["recording"]["release"].as_f64().unwrap();
    assert!(
        (-6.0..-2.0).contains(&release),
        "release at frame {release}: {err}"
    );
    // a = 0.843 m/s² on the marks' scale.
    let a = estimate_of(&r, "acceleration");
    assert!((a / 0.843 - 1.0).abs() < 0.03, "a {a}: {err}");
    // Right, and graded so: its halves in time are weighed with errors no smaller than the
    // whole answer's.
    assert_eq!(r["verdict"]["grade"], "ok", "{}", r["verdict"]);
}
