//! Interlaced recordings are read on their real clock: a camera's two fields a frame become two
//! frames at twice the rate, in the order they were taken, found from the picture (no tag
//! needed). Recordings made here: a disc swinging sideways drawn at 60 frames a second,
//! interlaced to 30 frames of two fields each by ffmpeg's `tinterlace`, top field first and
//! bottom field first, stored losslessly without a field-order tag.

mod util;

use std::path::Path;
use util::{estimate_of, need_ffmpeg, oscillator_run, stderr, write_frames_of, Estimate};

/// The disc's shift right of the centre (pixels) at time t: 9·e^(−0.1 t)·cos(2π t), so
/// γ0 = 4π² + 0.01 and γ1 = 0.2.
fn shift(t: f64) -> f64 {
    9.0 * (-0.1 * t).exp() * (2.0 * std::f64::consts::PI * t).cos()
}
const GAMMA0: f64 = 4.0 * std::f64::consts::PI * std::f64::consts::PI + 0.01;
/// Fields (frames drawn at 60 a second), two to a stored frame.
const FIELDS: usize = 360;

/// The swing interlaced with `mode` (`interleave_top` or `interleave_bottom`) into `dir`.
fn interlaced(dir: &Path, mode: &str) -> std::path::PathBuf {
    let frames = dir.join("frames");
    write_frames_of(&frames, FIELDS, 6.0, |k| (0.9, shift(k as f64 / 60.0)));
    let video = dir.join("swing.mkv");
    let o = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-y", "-framerate", "60", "-i"])
        .arg(frames.join("frame%d.png"))
        .args([
            "-vf",
            &format!("tinterlace=mode={mode},setfield=prog"),
            "-c:v",
            "ffv1",
            "-pix_fmt",
            "gray",
        ])
        .arg(&video)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    video
}

fn read_as_fields(mode: &str, order: &str) {
    if !need_ffmpeg() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let video = interlaced(dir.path(), mode);
    let (r, err) = oscillator_run(&video, &dir.path().join("run"), &[]);
    let rec = &r["recording"];
    assert_eq!(rec["info"]["fields"]["order"], order, "{}", rec["info"]);
    assert_eq!(rec["info"]["fields"]["by"], "picture");
    // Read as stored frames, the swing came at 30 a second, each frame its two fields' blend.
    assert_eq!(rec["fps"].as_f64(), Some(60.0), "{rec}");
    assert_eq!(rec["frames_decoded"].as_u64(), Some(FIELDS as u64), "{rec}");
    assert!(err.contains("interlaced ("), "{err}");
    let g0 = estimate_of(&r, "gamma0");
    assert!(
        (g0 / GAMMA0 - 1.0).abs() < 0.02,
        "gamma0 {g0} against {GAMMA0}"
    );
}

#[test]
fn top_field_first_is_read_as_fields_at_twice_the_rate() {
    read_as_fields("interleave_top", "top-first");
}

#[test]
fn bottom_field_first_is_read_as_fields_in_its_order() {
    read_as_fields("interleave_bottom", "bottom-first");
}

#[test]
fn a_progressive_recording_of_the_same_swing_is_read_as_frames() {
    if !need_ffmpeg() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let frames = dir.path().join("frames");
    write_frames_of(&frames, FIELDS / 2, 6.0, |k| (0.9, shift(k as f64 / 30.0)));
    let video = dir.path().join("swing.mkv");
    util::encode_lossless(&frames, &video, 30);
    let (r, _) = oscillator_run(&video, &dir.path().join("run"), &[]);
    let rec = &r["recording"];
    assert!(rec["info"]["fields"].is_null(), "{rec}");
    assert_eq!(rec["fps"].as_f64(), Some(30.0), "{rec}");
}

#[test]
fn fields_flag_reads_the_frames_or_refuses_an_image_folder() {
    if !need_ffmpeg() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let video = interlaced(dir.path(), "interleave_top");
    let (r, err) = oscillator_run(&video, &dir.path().join("run"), &["--fields", "frames"]);
    let rec = &r["recording"];
    assert!(rec["info"]["fields"].is_null(), "{rec}");
    assert_eq!(rec["fps"].as_f64(), Some(30.0), "{rec}");
    assert!(!err.contains("interlaced ("), "{err}");
    // An image folder's images are whole frames.
    let o = Estimate::new(dir.path().join("frames"))
        .args([
            "--model",
            "damped-oscillator",
            "--fps",
            "60",
            "--fields",
            "top-first",
        ])
        .out(&dir.path().join("folder"))
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--fields"), "{}", stderr(&o));
}
