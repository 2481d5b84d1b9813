//! Test helpers: `estimate` as a `TestCommand`, datasets rendered with gen's library as `gen`
//! would make them, and readers for report.json. Each test file uses part of it.
#![allow(dead_code)]

pub mod browser;
mod frames;
#[allow(unused_imports)]
pub use frames::gray_video;

pub use physvid_testkit::TestCommand;
#[allow(unused_imports)]
pub use physvid_testkit::{stderr, stdout};
use std::path::{Path, PathBuf};

/// `estimate` invocations.
pub struct Estimate;

impl Estimate {
    /// `estimate INPUT`.
    #[allow(clippy::new_ret_no_self)]
    pub fn new(input: impl AsRef<std::ffi::OsStr>) -> TestCommand {
        Estimate::bare().arg(input)
    }

    /// `estimate` with no input yet.
    pub fn bare() -> TestCommand {
        TestCommand::new(bin())
    }
}

/// `estimate --batch FILE --out OUT --epochs EPOCHS --quiet`.
pub fn batch(file: &Path, out: &Path, epochs: &str) -> TestCommand {
    Estimate::bare()
        .arg("--batch")
        .arg(file)
        .out(out)
        .args(["--epochs", epochs, "--quiet"])
}

/// `estimate FOLDER --fps 10 --model damped-oscillator --epochs 2`: a folder of
/// [`write_frames`]' images, read briefly.
pub fn folder_run(frames: &Path) -> TestCommand {
    Estimate::new(frames).args([
        "--fps",
        "10",
        "--model",
        "damped-oscillator",
        "--epochs",
        "2",
    ])
}

/// The `estimate` binary built for these tests.
pub fn bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_estimate"))
}

/// Renders a dataset into `dir` with gen's library, from the arguments `gen` would take
/// (`--scenario SCENARIO --out DIR --force EXTRA...`), and returns its path as text.
pub fn gen_dataset(dir: &Path, scenario: &str, extra: &[&str]) -> String {
    let out = dir.to_str().expect("UTF-8 temp path").to_string();
    let mut args = vec!["--scenario", scenario, "--out", &out, "--force"];
    args.extend_from_slice(extra);
    let cfg = generator::GenArgs::config_from(&args).expect("valid gen arguments");
    generator::generate_to_disk(&cfg).expect("gen writes the dataset");
    out
}

/// Reads `report.json` from an estimate output directory.
pub fn read_report(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("report.json")).expect("report.json written");
    serde_json::from_str(&text).expect("report.json is JSON")
}

/// The entry of parameter `name` in a report's `parameters`.
pub fn parameter<'a>(report: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    report["parameters"]
        .as_array()
        .expect("parameters array")
        .iter()
        .find(|p| p["name"] == name)
        .unwrap_or_else(|| panic!("no {name} in {report}"))
}

/// The law `name` among a report's track laws (`track.laws`).
pub fn track_law<'a>(report: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    report["track"]["laws"]
        .as_array()
        .expect("track laws array")
        .iter()
        .find(|l| l["law"] == name)
        .unwrap_or_else(|| panic!("no {name} law in {}", report["track"]))
}

/// `estimate VIDEO --epochs 20 --threads 1 --seed 1` into `out`, the model left to the tool
/// (the track's to guide), which must end with an estimate (exit 0 or 4): its output, stderr
/// and report.
pub fn guided_run(video: &Path, out: &Path) -> (std::process::Output, String, serde_json::Value) {
    let o = Estimate::new(video)
        .args(["--epochs", "20", "--threads", "1", "--seed", "1"])
        .out(out)
        .output();
    let err = stderr(&o);
    assert!(matches!(o.status.code(), Some(0 | 4)), "{err}");
    let report = read_report(out);
    (o, err, report)
}

/// The estimate of parameter `name` in a report.
pub fn estimate_of(report: &serde_json::Value, name: &str) -> f64 {
    parameter(report, name)["estimate"]
        .as_f64()
        .unwrap_or_else(|| panic!("no estimate for {name}"))
}

/// Writes a version-1 `.npy` file with header `descr` and `shape` and raw `data`.
pub fn write_npy(path: &Path, descr: &str, shape: &str, data: &[u8]) {
    let mut dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    bytes.extend_from_slice(dict.as_bytes());
    bytes.extend_from_slice(data);
    std::fs::write(path, bytes).unwrap();
}

/// Little-endian bytes of `values`.
pub fn f32_bytes(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Whether the ffmpeg command-line tools are on PATH.
pub fn ffmpeg_available() -> bool {
    ["ffmpeg", "ffprobe"].iter().all(|t| {
        std::process::Command::new(t)
            .arg("-version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Whether ffmpeg is there for a test (fails under CI=true when it is not; see
/// `physvid_testkit::require`).
pub fn need_ffmpeg() -> bool {
    physvid_testkit::require(
        "ffmpeg/ffprobe",
        ffmpeg_available(),
        "scripts/setup.sh installs Debian's ffmpeg",
    )
}

/// `../shared/real-videos/NAME` when it and ffmpeg are there; otherwise says why and `None`
/// (ffmpeg missing under CI=true fails; the shared folder, which no set-up provides, is
/// skipped visibly).
pub fn real_video(name: &str) -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/real-videos");
    let path = dir.join(name);
    if !need_ffmpeg() {
        return None;
    }
    if !path.exists() {
        eprintln!(
            "SKIPPED: {} is absent (the shared real-video folder is not in this checkout)",
            path.display()
        );
        return None;
    }
    Some(path)
}

/// Writes `n` grey PNG frames of a damped oscillator (a disc whose brightness follows z) into
/// `dir` as frame1.png … frameN.png.
pub fn write_frames(dir: &Path, n: usize) {
    write_disc_frames(dir, n, |k| {
        let t = k as f64 * 0.1;
        (-0.04 * t).exp() * (2.0 * t).cos()
    });
}

/// Writes `n` grey PNG frames of a disc whose brightness is 0.5 + 0.4·`z(k)` at frame k into
/// `dir` as frame1.png … frameN.png.
pub fn write_disc_frames(dir: &Path, n: usize, z: impl Fn(usize) -> f64) {
    write_frames_of(dir, n, 10.0, |k| (0.5 + 0.4 * z(k), 0.0));
}

/// Writes `n` grey 40×30 PNG frames of a disc of `radius` pixels whose (brightness, shift
/// right of the centre in pixels) at frame k is `disc(k)`, over a dark background, into `dir` as
/// frame1.png … frameN.png; each pixel's share of the disc from 4×4 samples, as a camera
/// averages its edge.
pub fn write_frames_of(dir: &Path, n: usize, radius: f64, disc: impl Fn(usize) -> (f64, f64)) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 0..n {
        let (b, shift) = disc(k);
        let img = image::GrayImage::from_fn(40, 30, |x, y| {
            let inside = (0..16)
                .filter(|s| {
                    let dx = x as f64 + (s % 4) as f64 / 4.0 + 0.125 - 20.5 - shift;
                    let dy = y as f64 + (s / 4) as f64 / 4.0 + 0.125 - 15.5;
                    dx * dx + dy * dy < radius * radius
                })
                .count();
            let cover = inside as f64 / 16.0;
            let v = 0.1 + (b - 0.1) * cover;
            image::Luma([(v * 255.0).round() as u8])
        });
        img.save(dir.join(format!("frame{}.png", k + 1))).unwrap();
    }
}

/// `frames` frames of a `size` picture at `fps`, the ball at `centre(k)` in frame k, as a
/// lossless grey video `dir/ball.mkv`: a light ball of radius 5 on a dark wall, each pixel's
/// share of it from 4×4 samples.
pub fn ball_video(
    dir: &Path,
    size: (u32, u32),
    frames: usize,
    fps: u32,
    centre: impl Fn(usize) -> (f64, f64),
) -> PathBuf {
    gray_video(dir, "ball.mkv", (frames, fps), size, |k, x, y| {
        let (cx, cy) = centre(k);
        let inside = (0..16)
            .filter(|s| {
                let dx = x as f64 + (s % 4) as f64 / 4.0 + 0.125 - cx;
                let dy = y as f64 + (s / 4) as f64 / 4.0 + 0.125 - cy;
                dx * dx + dy * dy < 25.0
            })
            .count();
        (25.0 + 200.0 * inside as f64 / 16.0).round() as u8
    })
}

/// Encodes `frames/frame%d.png` into `video`, a lossless grey FFV1 file at `fps`.
pub fn encode_lossless(frames: &Path, video: &Path, fps: u32) {
    encode_ffv1(frames, video, fps, "gray")
}

/// Encodes `frames/frame%d.png` into `video`, an FFV1 file at `fps` in ffmpeg's pixel format
/// `pix_fmt` (`yuv420p`: the colour at half the resolution, as phones store it).
pub fn encode_ffv1(frames: &Path, video: &Path, fps: u32, pix_fmt: &str) {
    let o = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-framerate", &fps.to_string(), "-i"])
        .arg(frames.join("frame%d.png"))
        .args(["-c:v", "ffv1", "-pix_fmt", pix_fmt])
        .arg(video)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A damped oscillator's disc (`write_frames`, 120 frames) in `dir`/frames and as a lossless
/// video `dir`/clip.mkv at `fps`: (frames, video).
pub fn oscillator_video(dir: &Path, fps: u32) -> (PathBuf, PathBuf) {
    let frames = dir.join("frames");
    write_frames(&frames, 120);
    let video = dir.join("clip.mkv");
    encode_lossless(&frames, &video, fps);
    (frames, video)
}

/// `estimate VIDEO --model damped-oscillator --seed 1 EXTRA` into `out`, which must end with
/// an estimate (exit 0 or 4): its report and stderr.
pub fn oscillator_run(video: &Path, out: &Path, extra: &[&str]) -> (serde_json::Value, String) {
    let o = Estimate::new(video)
        .args(["--model", "damped-oscillator", "--seed", "1"])
        .args(extra)
        .out(out)
        .output();
    assert!(
        matches!(o.status.code(), Some(0 | 4)),
        "{}: {}",
        video.display(),
        stderr(&o)
    );
    (read_report(out), stderr(&o))
}

/// summary.csv without its wall_s column (the one thing that differs between runs).
pub fn without_wall(csv: &str) -> Vec<String> {
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let wall = header.iter().position(|h| *h == "wall_s").unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let mut rows = vec![header.join(",")];
    for r in reader.records() {
        let r = r.unwrap();
        let cells: Vec<&str> = r
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != wall)
            .map(|(_, c)| c)
            .collect();
        rows.push(cells.join("\u{1f}"));
    }
    rows
}

/// The first value in SI of the track's chosen law in report.json (a constant acceleration's, in
/// m/s²); NaN where there is none.
pub fn track_si(report: &serde_json::Value) -> f64 {
    report["track"]["laws"]
        .as_array()
        .unwrap()
        .iter()
        .find(|l| l["law"] == report["track"]["chosen"])
        .and_then(|l| l["si"][0]["value"].as_f64())
        .unwrap_or(f64::NAN)
}

/// A swing's angle (radians from the vertical) at each of `frames` frames at `fps`:
/// θ'' = −(g/L) sin θ − `damping` θ' from `start_deg` at rest (RK4, a hundred steps a frame).
pub fn swing_angles(
    frames: usize,
    fps: u32,
    g_over_l: f64,
    damping: f64,
    start_deg: f64,
) -> Vec<f64> {
    let f = |a: f64, v: f64| (v, -g_over_l * a.sin() - damping * v);
    let h = 1.0 / (fps as f64 * 100.0);
    let mut s = (start_deg.to_radians(), 0.0);
    let mut out = Vec::with_capacity(frames);
    for _ in 0..frames {
        out.push(s.0);
        for _ in 0..100 {
            let k1 = f(s.0, s.1);
            let k2 = f(s.0 + 0.5 * h * k1.0, s.1 + 0.5 * h * k1.1);
            let k3 = f(s.0 + 0.5 * h * k2.0, s.1 + 0.5 * h * k2.1);
            let k4 = f(s.0 + h * k3.0, s.1 + h * k3.1);
            s.0 += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            s.1 += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
    }
    out
}
