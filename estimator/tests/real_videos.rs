//! End-to-end tests on the shared phone recordings (`../shared/real-videos`, skipped visibly
//! where that folder is absent): the pendulum's g/L from its period and its damping, the
//! Torricelli jar's level and k in SI (and a stride of its own on a short trim), the dropped
//! ball's constant acceleration and g in SI (also with the floor at its impact as a reading),
//! each with the verdict it gets.

mod util;

use std::path::Path;
use util::{estimate_of, read_report, real_video, stderr, Estimate};

fn estimate(args: &[&str], out: &Path) -> (serde_json::Value, String) {
    let o = Estimate::bare().args(args).out(out).quiet().estimated();
    (read_report(out), stderr(&o))
}

/// The verdict's grade of a report.
fn grade(r: &serde_json::Value) -> &str {
    r["verdict"]["grade"].as_str().unwrap()
}

#[test]
fn real_pendulum_gives_g_over_l_from_its_period() {
    let Some(video) = real_video("pendulum-redapple.mov") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let (r, _) = estimate(
        &[video.to_str().unwrap(), "--model", "pendulum", "--preview"],
        &tmp.path().join("run"),
    );
    // The period measured by tracking the bob, T = 2.077 s, gives g/L = 9.15 s⁻².
    let w2 = estimate_of(&r, "g_over_l");
    assert!((w2 / 9.15 - 1.0).abs() < 0.05, "g/L {w2}");
    assert_eq!(
        r["recording"]["stride"], 6,
        "Table 5's dt 0.1 s at 59.94 fps"
    );
    // Tracking the red bob's horizontal position frame by frame, its swing amplitude decays
    // as e^(−ζt/2) with ζ = 0.017 s⁻¹ (README); the damping solved on the whole timeline
    // finds it, and A.6's fit of the encoded swings' amplitudes agrees.
    let zeta = estimate_of(&r, "damping");
    assert!((zeta / 0.017 - 1.0).abs() < 0.25, "damping {zeta}");
    assert_eq!(r["cross_check"]["agrees"], true, "{}", r["cross_check"]);
    // The verdict agrees: nothing against this answer.
    assert_eq!(grade(&r), "ok", "{}", r["verdict"]);
    for f in ["timeline.png", "timeline.csv", "clips.png", "latents.png"] {
        assert!(tmp.path().join("run").join(f).exists(), "{f}");
    }
    let csv = std::fs::read_to_string(tmp.path().join("run/timeline.csv")).unwrap();
    assert!(csv.starts_with("time_s,z\n"));
    assert_eq!(
        csv.lines().count() as u64,
        1 + r["recording"]["frames_decoded"].as_u64().unwrap()
    );
}

/// The Torricelli jar after the hand and the sloshing, before it runs dry; dt 0.5 s.
const TORRICELLI_CLIPS: [&str; 8] = [
    "--model",
    "torricelli",
    "--start",
    "3",
    "--end",
    "20",
    "--stride",
    "15",
];

#[test]
fn real_torricelli_fit_explains_the_level_in_latent_units() {
    let Some(video) = real_video("torricelli-500ml.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut args = vec![video.to_str().unwrap()];
    args.extend(TORRICELLI_CLIPS);
    let (r, err) = estimate(&args, &tmp.path().join("run"));
    let residual = r["best_val_rel_mse"].as_f64().unwrap();
    assert!(
        residual < 0.15,
        "the fitted law leaves {residual} of the variance"
    );
    assert_eq!(r["parameters"][0]["name"], "k_latent");
    assert_eq!(r["parameters"][0]["units"], "latent");
    assert!(estimate_of(&r, "k_latent") > 0.0);
    assert!(err.contains("--reference"), "{err}");
}

#[test]
fn a_trim_too_short_for_table_5s_clip_gets_a_shorter_stride_not_a_refusal() {
    let Some(video) = real_video("torricelli-500ml.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // 13.75 s at 29.97 fps: one clip of Table 5's 20 frames 1 s apart would need 571 frames.
    let (r, err) = estimate(
        &[
            video.to_str().unwrap(),
            "--model",
            "torricelli",
            "--start",
            "7",
            "--end",
            "20.75",
            "--epochs",
            "5",
        ],
        &tmp.path().join("run"),
    );
    let stride = r["recording"]["stride"].as_u64().unwrap();
    let kept = r["recording"]["frames_decoded"].as_u64().unwrap();
    assert!(
        stride < 30 && 19 * stride <= kept / 2,
        "stride {stride} of {kept} frames"
    );
    assert!(err.contains("--stride chooses"), "{err}");
}

#[test]
fn real_free_fall_finds_a_constant_acceleration_and_takes_the_capture_rate() {
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let v = video.to_str().unwrap();
    // From the release (frame ~120 of 30 fps container time) to just before the floor.
    let common = [
        v,
        "--model",
        "free-fall",
        "--start",
        "4.0",
        "--end",
        "6.5",
        "--size",
        "16x160",
    ];
    let mut with_fps = common.to_vec();
    with_fps.extend(["--fps", "120"]);
    let (r, err) = estimate(&with_fps, &tmp.path().join("a"));
    assert!(!err.contains("capture.fps"), "{err}");
    // Over the 0.5 s of fall the parabola moves the latent by many of its standard deviations.
    // (The validation clips, the last fifth, hold the noisy frames before the impact.)
    let a = estimate_of(&r, "acceleration_latent");
    let std = r["latent_std"].as_f64().unwrap();
    assert!(
        a.abs() * 0.5 * 0.5 / 2.0 > 2.0 * std,
        "a {a}, latent std {std}"
    );
    let mut without = common.to_vec();
    without.extend(["--epochs", "2"]);
    let (r, err) = estimate(&without, &tmp.path().join("b"));
    // Without --fps the capture tag's rate is taken, and said to be.
    assert!(err.contains("com.android.capture.fps"), "{err}");
    assert_eq!(r["recording"]["fps_source"], "capture tag");
    assert_eq!(r["recording"]["fps"], 120.0);
}

#[test]
fn real_free_fall_with_time_references_gives_g_in_si() {
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // Read off the video (docs/recordings.md): the ball leaves its rest at 3.933 s of the
    // container's timeline and has fallen 1.975 m at 6.5 s. No trim: the release and the
    // impact are found in the frames.
    let (r, err) = estimate(
        &[
            video.to_str().unwrap(),
            "--model",
            "free-fall",
            "--fps",
            "120",
            "--size",
            "16x160",
            "--reference",
            "3.933s=0,6.5s=1.975",
        ],
        &tmp.path().join("run"),
    );
    assert!(err.contains("motion from rest"), "{err}");
    assert_eq!(r["config"]["encoder"], "centroid");
    let rec = &r["recording"];
    let (start, end) = (rec["start"].as_f64().unwrap(), rec["end"].as_f64().unwrap());
    // Released near container frame 119–121, on the floor at 201–202.
    assert!(start > 3.5 && start < 3.933, "kept from {start} s");
    assert!(end > 6.5 && end < 6.72, "kept to {end} s");
    // The camera's perspective bends a pixel-to-metre scale by 10–14 % (README of the
    // recordings); the classical value from the release and the impact is 9.31 m/s².
    let g = estimate_of(&r, "g");
    assert!((g / 9.81 - 1.0).abs() < 0.03, "g {g}");
    assert_ne!(grade(&r), "unreliable", "{}", r["verdict"]);
    // The hand that held the ball opens beside it as it drops (docs/recordings.md): in grey the
    // first frames of the descent measure more than the ball and pull the release 1.5 frames
    // late; the ball's red sets it apart from the skin, and read by it the release is within
    // 0.6 frame of where its colour at full resolution put it (frame 117.96–118.1, outside the
    // tool), the verdict finding nothing against it.
    let d = &rec["descent"];
    assert_eq!(d["colour"], true, "{d}\n{err}");
    let release = d["release"].as_f64().unwrap();
    assert!((117.4..118.6).contains(&release), "release {release}");
    let reasons = r["verdict"]["reasons"].as_array().unwrap();
    assert!(
        !reasons.iter().any(|x| x["check"] == "release"),
        "{reasons:?}"
    );
}

#[test]
fn real_free_fall_read_with_the_floor_at_the_impact() {
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // Issue 64: the floor, 2.26 m below the ball at rest, reached at the impact (6.7 s), a
    // frame or three after the descent kept ends: read on the law's rollout, not refused (a
    // pendulum was chosen when free fall refused it). The model chosen by the tool.
    let (r, err) = estimate(
        &[
            video.to_str().unwrap(),
            "--seed",
            "0",
            "--reference",
            "3.933s=0,6.7s=2.26",
        ],
        &tmp.path().join("run"),
    );
    assert_eq!(r["model"], "free-fall", "{err}");
    assert!(err.contains("past its last"), "{err}");
    let g = estimate_of(&r, "g");
    assert!((g / 9.81 - 1.0).abs() < 0.03, "g {g}: {err}");
    assert_eq!(grade(&r), "ok", "{}", r["verdict"]);
}

#[test]
fn real_torricelli_with_time_references_gives_k_in_si() {
    let Some(video) = real_video("torricelli-500ml.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // README's command: levels read off single frames, 7.27 cm at 3.0 s, 3.73 cm at 12.0 s;
    // no trim (the hand's frames found still and left out, the stride shortened to fit).
    let args = [
        video.to_str().unwrap(),
        "--model",
        "torricelli",
        "--reference",
        "3.0s=0.0727,12.0s=0.0373",
    ];
    let (r, _) = estimate(&args, &tmp.path().join("run"));
    assert_eq!(r["parameters"][0]["units"], "SI");
    // Appendix Eq. 23's two-point k from the same two readings.
    let two_point = 2.0 * (0.0727f64.sqrt() - 0.0373f64.sqrt()) / 9.0;
    let k = estimate_of(&r, "k");
    assert!(
        (k / two_point - 1.0).abs() < 0.03,
        "k {k} against {two_point}"
    );
    assert_eq!(grade(&r), "ok", "{}", r["verdict"]);
}
