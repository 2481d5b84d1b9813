//! Issue 50's class "silently wrong numbers": a recording's clock is read from its frames' own
//! times (a GIF's delays, a variable-frame-rate file's timestamps, an image folder's numbers),
//! never from their median interval; frames a clock places unevenly are resampled onto it,
//! a dropped frame filled in, a doubled one left out, a first frame off the clock left out
//! (issue 64), and what fits no even clock refused with the numbers. Recordings made here with ffmpeg; each test fails on the code before.

mod util;

use std::path::{Path, PathBuf};
use util::{estimate_of, need_ffmpeg, oscillator_run, write_disc_frames, Estimate};

/// The disc's brightness: z(t) = e^(−0.1 t)·cos(π t), so γ0 = π² + 0.01 and γ1 = 0.2.
fn z(t: f64) -> f64 {
    (-0.1 * t).exp() * (std::f64::consts::PI * t).cos()
}
const GAMMA0: f64 = std::f64::consts::PI * std::f64::consts::PI + 0.01;

/// Runs ffmpeg with `args`, asserting success.
fn ffmpeg(args: &[&str]) {
    let o = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-y"])
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Frames of the swing at the real times `times` (s) as frame1.png … in `dir`.
fn frames_at(dir: &Path, times: &[f64]) {
    write_disc_frames(dir, times.len(), |k| z(times[k]));
}

/// The swing's frames `dir/frames` at the times `setpts` (ffmpeg's expression of the frame
/// number N, in seconds) gives them, as `times` says them, in a lossless `dir/clip.mkv`
/// whose packets carry those times (a millisecond time base).
fn video_at(dir: &Path, times: &[f64], setpts: &str) -> PathBuf {
    let frames = dir.join("frames");
    frames_at(&frames, times);
    let video = dir.join("clip.mkv");
    ffmpeg(&[
        "-framerate",
        "30",
        "-i",
        frames.join("frame%d.png").to_str().unwrap(),
        "-vf",
        &format!("settb=1/1000,setpts='({setpts})/TB'"),
        "-fps_mode",
        "passthrough",
        "-enc_time_base",
        "1/1000",
        "-c:v",
        "ffv1",
        "-pix_fmt",
        "gray",
        video.to_str().unwrap(),
    ]);
    video
}

#[test]
fn a_gif_is_read_at_its_own_rate_not_its_median_delay() {
    if !need_ffmpeg() {
        return;
    }
    for fps in [30.0, 24.0] {
        let tmp = tempfile::tempdir().unwrap();
        let times: Vec<f64> = (0..240).map(|k| k as f64 / fps).collect();
        let frames = tmp.path().join("frames");
        frames_at(&frames, &times);
        let gif = tmp.path().join("clip.gif");
        ffmpeg(&[
            "-framerate",
            &fps.to_string(),
            "-i",
            frames.join("frame%d.png").to_str().unwrap(),
            gif.to_str().unwrap(),
        ]);
        let (report, err) = oscillator_run(&gif, &tmp.path().join("run"), &[]);
        let read = report["recording"]["fps"].as_f64().unwrap();
        assert!(
            (read / fps - 1.0).abs() < 0.003,
            "{fps} fps read as {read}: {err}"
        );
        let g0 = estimate_of(&report, "gamma0");
        assert!(
            (g0 / GAMMA0 - 1.0).abs() < 0.03,
            "{fps} fps: γ0 {g0}: {err}"
        );
    }
}

#[test]
fn uneven_frame_times_are_resampled_onto_their_clock() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // Intervals d, d, 1.45d over and over (d = 1/30 s): their mean, 1.15d, is the clock.
    let d = 1.0 / 30.0;
    let times: Vec<f64> = (0..240)
        .map(|n| ((n / 3) as f64 * 3.45 + (n % 3) as f64) * d)
        .collect();
    let video = video_at(tmp.path(), &times, "(floor(N/3)*3.45+mod(N,3))/30");
    let (report, err) = oscillator_run(&video, &tmp.path().join("run"), &[]);
    let read = report["recording"]["fps"].as_f64().unwrap();
    assert!(
        (read * 1.15 * d - 1.0).abs() < 0.01,
        "read at {read} fps: {err}"
    );
    assert!(err.contains("resampled onto it"), "{err}");
    let g0 = estimate_of(&report, "gamma0");
    assert!((g0 / GAMMA0 - 1.0).abs() < 0.05, "γ0 {g0}: {err}");
}

#[test]
fn dropped_frames_are_filled_in_and_a_pause_is_refused_with_its_numbers() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // 30 fps with the frames at slots 80 and 161 never recorded (a phone's variable rate).
    let times: Vec<f64> = (0..242)
        .filter(|k| *k != 80 && *k != 161)
        .map(|k| k as f64 / 30.0)
        .collect();
    let video = video_at(
        &tmp.path().join("dropped"),
        &times,
        "(N+gte(N,80)+gte(N,160))/30",
    );
    let (report, err) = oscillator_run(&video, &tmp.path().join("run"), &[]);
    assert!(err.contains("2 dropped frames filled in"), "{err}");
    let g0 = estimate_of(&report, "gamma0");
    assert!((g0 / GAMMA0 - 1.0).abs() < 0.03, "γ0 {g0}: {err}");
    // A pause of half a second in the capture: refused, with where it is.
    let times: Vec<f64> = (0..240)
        .filter(|k| !(100..115).contains(k))
        .map(|k| k as f64 / 30.0)
        .collect();
    let video = video_at(&tmp.path().join("paused"), &times, "(N+15*gte(N,100))/30");
    Estimate::new(&video)
        .args(["--model", "damped-oscillator"])
        .out(&tmp.path().join("paused-run"))
        .bad_input("15 frames are missing after 3.");
}

#[test]
fn a_first_frame_off_the_clock_is_left_out_and_the_rest_read() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    // A museum camera's clock: 52.9 ms to the second frame, then 30 fps (the first frame 41 %
    // of an interval off the clock the others keep). It was refused: "re-encode".
    let times: Vec<f64> = (0..241)
        .map(|k| match k {
            0 => 0.0,
            k => 0.053 + (k - 1) as f64 / 30.0,
        })
        .collect();
    let video = video_at(tmp.path(), &times, "if(eq(N,0),0,0.053+(N-1)/30)");
    let (report, err) = oscillator_run(&video, &tmp.path().join("run"), &[]);
    assert!(err.contains("the first frame (off the clock"), "{err}");
    let read = report["recording"]["fps"].as_f64().unwrap();
    assert!(
        (read / 30.0 - 1.0).abs() < 0.003,
        "read at {read} fps: {err}"
    );
    // The part read starts at the second frame, on the file's timeline.
    let start = report["recording"]["start"].as_f64().unwrap_or(0.0);
    assert!((start - 0.053).abs() < 0.002, "start {start}: {err}");
    let g0 = estimate_of(&report, "gamma0");
    assert!((g0 / GAMMA0 - 1.0).abs() < 0.03, "γ0 {g0}: {err}");
    // One frame in the middle 40 % of an interval late: resampled on the real times.
    let times: Vec<f64> = (0..240)
        .map(|k| k as f64 / 30.0 + if k == 120 { 0.013 } else { 0.0 })
        .collect();
    let video = video_at(&tmp.path().join("late"), &times, "N/30+0.013*eq(N,120)");
    let (report, err) = oscillator_run(&video, &tmp.path().join("late-run"), &[]);
    assert!(err.contains("resampled onto it"), "{err}");
    let g0 = estimate_of(&report, "gamma0");
    assert!((g0 / GAMMA0 - 1.0).abs() < 0.03, "γ0 {g0}: {err}");
}

#[test]
fn an_image_folder_is_read_on_its_numbers() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    let times: Vec<f64> = (0..240).map(|k| k as f64 / 30.0).collect();
    frames_at(&frames, &times);
    // frame101.png, the swing at 100/30 s, is missing: the next image is 101/30 s, not 100/30.
    std::fs::remove_file(frames.join("frame101.png")).unwrap();
    let (report, err) = oscillator_run(&frames, &tmp.path().join("run"), &["--fps", "30"]);
    assert!(err.contains("1 dropped frame filled in"), "{err}");
    assert_eq!(report["recording"]["frames_decoded"], 240, "{err}");
}
