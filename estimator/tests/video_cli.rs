//! End-to-end tests of `estimate` on recordings: the real phone videos of `../shared/real-videos`
//! (skipped with a message when that folder or ffmpeg is absent), image folders against videos of
//! the same frames, and bad recordings.

mod util;

use std::path::Path;
use std::process::Command;
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
fn real_free_fall_finds_a_constant_acceleration_and_flags_the_capture_rate() {
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
    assert!(err.contains("com.android.capture.fps"), "{err}");
    assert_eq!(r["recording"]["fps_source"], "container");
}

/// Writes `n` grey PNG frames of a damped oscillator (a disc whose brightness follows z) into
/// `dir` as frame1.png … frameN.png.
fn write_frames(dir: &Path, n: usize) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 0..n {
        let t = k as f64 * 0.1;
        let z = (-0.04 * t).exp() * (2.0 * t).cos();
        let img = image::GrayImage::from_fn(40, 30, |x, y| {
            let (dx, dy) = (x as f64 - 20.0, y as f64 - 15.0);
            let v = if dx * dx + dy * dy < 100.0 {
                0.5 + 0.4 * z
            } else {
                0.1
            };
            image::Luma([(v * 255.0).round() as u8])
        });
        img.save(dir.join(format!("frame{}.png", k + 1))).unwrap();
    }
}

/// Encodes `frames/frame%d.png` into `video`, a lossless grey FFV1 file at 10 fps.
fn encode_lossless(frames: &Path, video: &Path) {
    let o = Command::new("ffmpeg")
        .args(["-v", "error", "-framerate", "10", "-i"])
        .arg(frames.join("frame%d.png"))
        .args(["-c:v", "ffv1", "-pix_fmt", "gray"])
        .arg(video)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn an_image_folder_and_a_video_of_the_same_frames_give_the_same_estimate() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames(&frames, 120);
    // A lossless grey video of the same frames at 10 fps.
    let video = tmp.path().join("clip.mkv");
    encode_lossless(&frames, &video);
    let args = [
        "--model",
        "damped-oscillator",
        "--size",
        "20x15",
        "--epochs",
        "8",
        "--threads",
        "1",
    ];
    let mut a = vec![frames.to_str().unwrap(), "--fps", "10"];
    a.extend(args);
    let (ra, _) = estimate(&a, &tmp.path().join("a"));
    let mut b = vec![video.to_str().unwrap()];
    b.extend(args);
    let (rb, _) = estimate(&b, &tmp.path().join("b"));
    assert_eq!(ra["recording"]["clips"], rb["recording"]["clips"]);
    assert_eq!(ra["recording"]["stride"], 2, "dt 0.2 s at 10 fps");
    for name in ["gamma0", "gamma1"] {
        assert_eq!(estimate_of(&ra, name), estimate_of(&rb, name), "{name}");
    }
}

#[test]
fn bad_recordings_get_a_one_line_error_and_exit_code_2() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let t = tmp.path();
    let frames = t.join("frames");
    write_frames(&frames, 60);
    let video = t.join("clip.mkv");
    encode_lossless(&frames, &video);
    let bytes = std::fs::read(&video).unwrap();
    let truncated = t.join("truncated.mkv");
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    // 200 bytes zeroed in the middle: used to give 41 of 60 frames in silence.
    let mut zeroed = bytes.clone();
    let mid = zeroed.len() / 2;
    zeroed[mid..mid + 200].fill(0);
    let damaged = t.join("damaged.mkv");
    std::fs::write(&damaged, &zeroed).unwrap();
    // Image folders with a truncated and an empty image: used to skip it (later frames shifted
    // in time) or to stop without naming it.
    let folder = |name: &str, bad: &str, keep: usize| {
        let dir = t.join(name);
        write_frames(&dir, 12);
        let img = dir.join(bad);
        let png = std::fs::read(&img).unwrap();
        std::fs::write(&img, &png[..keep.min(png.len() / 2)]).unwrap();
        dir.to_str().unwrap().to_string()
    };
    let truncated_png = folder("cut", "frame5.png", usize::MAX);
    let empty_png = folder("zero", "frame7.png", 0);
    let text = t.join("notes.mp4");
    std::fs::write(&text, "not a video at all\n").unwrap();
    let empty = t.join("empty");
    std::fs::create_dir(&empty).unwrap();
    std::fs::write(empty.join("readme.txt"), "no images").unwrap();
    let v = video.to_str().unwrap();
    let m = ["--model", "damped-oscillator"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![text.to_str().unwrap()], "not a readable video"),
        (vec![truncated.to_str().unwrap()], "truncated"),
        (vec![damaged.to_str().unwrap()], "damaged"),
        (
            vec![&truncated_png, "--fps", "10"],
            "frame5.png: image 5 of 12 in the folder does not decode",
        ),
        (
            vec![&empty_png, "--fps", "10"],
            "frame7.png: image 7 of 12 in the folder does not decode (an empty file)",
        ),
        (vec![v, "--start", "100"], "no frames between --start 100"),
        (vec![v, "--crop", "30,20,20,20"], "outside the 40×30 frame"),
        (vec![v, "--frames-per-clip", "40"], "one clip of 40 frames"),
        (
            vec![v, "--start", "3", "--end", "2"],
            "--end 2 is not after --start 3",
        ),
        (vec![frames.to_str().unwrap()], "--fps"),
        (vec![v, "--size", "3x3"], "--size"),
        (
            vec![empty.to_str().unwrap(), "--fps", "10"],
            "nor an image folder (no .png",
        ),
    ];
    let out = t.join("run");
    for (args, needle) in cases {
        Estimate::bare()
            .args(args)
            .args(m)
            .out(&out)
            .args(["--epochs", "1"])
            .bad_input(needle);
    }
    // A recording needs --model; ffmpeg missing is named with the fix.
    let o = Estimate::new(v).out(&out).output();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--model"), "{}", stderr(&o));
    let o = Estimate::new(v)
        .args(["--model", "damped-oscillator"])
        .out(&out)
        .env("PATH", t.join("nowhere"))
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("install ffmpeg"), "{}", stderr(&o));
}

#[test]
fn references_by_time_land_on_the_clip_frame_at_that_time() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames(&frames, 60);
    let out = tmp.path().join("run");
    // 10 fps, the pendulum's 20-frame clips at stride 1: clip c starts at frame c.
    let run = |refs: &str| {
        Estimate::new(&frames)
            .args(["--fps", "10", "--model", "pendulum", "--reference", refs])
            .args(["--epochs", "1", "--threads", "1"])
            .out(&out)
    };
    run("1.0s=0.2,3.5s=-0.1").quiet().estimated();
    let r = read_report(&out);
    let refs = r["calibration"]["reference"].as_array().unwrap();
    assert_eq!(refs.len(), 2, "{refs:?}");
    assert_eq!(refs[0], serde_json::json!([10, 0, 0.2]));
    assert_eq!(refs[1], serde_json::json!([35, 0, -0.1]));
    run("1.0s=0.2,7.0s=-0.1")
        .bad_input("--reference 7s: outside the part of the recording kept, 0–5.9 s");
    run("1.0s=0.2,1.02s=0.3").bad_input("1s=0.2 and 1.02s=0.3 fall on the same frame");
}

#[test]
fn real_free_fall_with_time_references_gives_g_in_si() {
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // Read off the video (README): the ball leaves its rest at 3.933 s of the container's
    // timeline and has fallen 2.26 m at 6.70 s, just above the floor.
    let (r, _) = estimate(
        &[
            video.to_str().unwrap(),
            "--model",
            "free-fall",
            "--fps",
            "120",
            "--start",
            "3.933",
            "--end",
            "6.72",
            "--size",
            "16x160",
            "--reference",
            "3.933s=0,6.7s=2.26",
        ],
        &tmp.path().join("run"),
    );
    let g = estimate_of(&r, "g");
    assert!((g / 9.81 - 1.0).abs() < 0.15, "g {g}");
}

#[test]
fn real_torricelli_with_time_references_gives_k_in_si() {
    let Some(video) = real_video("torricelli-500ml.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    // Levels read off single frames (README): 7.27 cm at 3.0 s, 3.73 cm at 12.0 s.
    let mut args = vec![video.to_str().unwrap()];
    args.extend(TORRICELLI_CLIPS);
    args.extend(["--reference", "3.0s=0.0727,12.0s=0.0373"]);
    let (r, _) = estimate(&args, &tmp.path().join("run"));
    assert_eq!(r["parameters"][0]["units"], "SI");
    // Appendix Eq. 23's two-point k from the same two readings.
    let two_point = 2.0 * (0.0727f64.sqrt() - 0.0373f64.sqrt()) / 9.0;
    let k = estimate_of(&r, "k");
    assert!(
        (k / two_point - 1.0).abs() < 0.05,
        "k {k} against {two_point}"
    );
    assert_eq!(grade(&r), "ok", "{}", r["verdict"]);
}
