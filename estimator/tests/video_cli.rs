//! End-to-end tests of `estimate` on recordings made here: image folders against videos of the
//! same frames, references by time, and bad recordings (the shared phone recordings are in
//! real_videos.rs).

mod util;

use std::path::Path;
use util::{
    encode_lossless, estimate_of, oscillator_video, read_report, stderr, write_frames, Estimate,
};

fn estimate(args: &[&str], out: &Path) -> (serde_json::Value, String) {
    let o = Estimate::bare().args(args).out(out).quiet().estimated();
    (read_report(out), stderr(&o))
}

#[test]
fn an_image_folder_and_a_video_of_the_same_frames_give_the_same_estimate() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // The frames, and a lossless grey video of them at 10 fps.
    let (frames, video) = oscillator_video(tmp.path(), 10);
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
    encode_lossless(&frames, &video, 10);
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
        (
            vec![v, "--frames-per-clip", "40", "--stride", "2"],
            "one clip of 40 frames",
        ),
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
    // ffmpeg missing is named with the fix.
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
fn the_still_frames_before_a_release_are_left_out_and_one_clips_span_of_the_settled_ones_kept() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // Held at its release brightness for 3 s (the swing turns there: the first frame or two
    // after are as still), released into a swing that dies out within about 8 s, then settled
    // for 10 s; 10 fps.
    let frames = tmp.path().join("frames");
    util::write_disc_frames(&frames, 250, |k| match k {
        0..30 => 1.0,
        _ => {
            let t = (k - 30) as f64 * 0.1;
            (-0.5 * t).exp() * (2.0 * t).cos()
        }
    });
    let video = tmp.path().join("clip.mkv");
    encode_lossless(&frames, &video, 10);
    let v = video.to_str().unwrap();
    let args = [
        "--model",
        "damped-oscillator",
        "--size",
        "20x15",
        "--epochs",
        "4",
    ];
    let (r, err) = estimate(&[&[v][..], &args[..]].concat(), &tmp.path().join("a"));
    let rec = &r["recording"];
    let (start, end) = (rec["start"].as_f64().unwrap(), rec["end"].as_f64().unwrap());
    assert!((2.85..=3.25).contains(&start), "kept from {start} s\n{err}");
    // The swing is within 5 % of its range by about 6 s in; a clip spans 19 × 0.2 s.
    let span = 19.0 * 0.1 * rec["stride"].as_f64().unwrap();
    assert!(
        end < 24.9 && end > 6.0 + span,
        "kept to {end} s (clip span {span})"
    );
    assert!(err.contains("the picture is still before"), "{err}");
    // --start and --end keep what they say.
    let (r, _) = estimate(
        &[&[v, "--start", "0", "--end", "24.9"][..], &args[..]].concat(),
        &tmp.path().join("b"),
    );
    assert_eq!(r["recording"]["start"].as_f64(), Some(0.0));
    assert_eq!(r["recording"]["frames_decoded"].as_u64(), Some(249));
}

#[test]
fn one_object_moving_about_the_frame_is_read_by_its_position_and_a_brightness_is_not() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // A disc of radius 3 swinging ±14 px, damped: γ0 = 9.01 s⁻², γ1 = 0.2 s⁻¹; 20 fps, 10 s.
    let swing = tmp.path().join("swing");
    util::write_frames_of(&swing, 200, 3.0, |k| {
        let t = k as f64 / 20.0;
        (0.9, 14.0 * (-0.1 * t).exp() * (3.0 * t).cos())
    });
    let args = ["--model", "damped-oscillator", "--threads", "1"];
    let (r, _) = estimate(
        &[&[swing.to_str().unwrap(), "--fps", "20"][..], &args[..]].concat(),
        &tmp.path().join("a"),
    );
    assert_eq!(r["config"]["encoder"], "centroid", "{}", r["config"]);
    let note = r["config"]["encoder_note"].as_str().unwrap();
    assert!(note.contains("an object moves about"), "{note}");
    let g1 = estimate_of(&r, "gamma1");
    assert!((g1 / 0.2 - 1.0).abs() < 0.05, "gamma1 {g1}");
    // A disc in place, its brightness swinging: the model's own encoder.
    let glow = tmp.path().join("glow");
    write_frames(&glow, 60);
    let (r, _) = estimate(
        &[
            &[glow.to_str().unwrap(), "--fps", "10", "--epochs", "1"][..],
            &args[..],
        ]
        .concat(),
        &tmp.path().join("b"),
    );
    assert_eq!(r["config"]["encoder"], "small");
}
