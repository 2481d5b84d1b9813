//! Issue 20's classes of hostile input for `estimate`, one test each, fixed where they arise:
//! a recording's timing judged by its frames' own timestamps, the pixel values' scale, names
//! and flags given twice, impossible calibrations, inputs that block and unbounded work, runs
//! that give no estimate, pictures too small to carry one, a model without oscillation judged
//! as one, and a healthy file whose container holds frames it never shows (`gen`'s classes are
//! in generator/tests/hostile_gen.rs).

mod util;

use std::path::{Path, PathBuf};
use util::{gen_dataset, read_report, stderr, Estimate};

/// A small intensity set (60 clips of 16×16) and its frames as a bare array.
fn small(dir: &Path) -> (String, PathBuf) {
    let data = gen_dataset(
        &dir.join("set"),
        "intensity",
        &["--samples", "60", "--size", "16", "--seed", "3"],
    );
    (data.clone(), PathBuf::from(data).join("frames.npy"))
}

#[test]
fn a_hot_pixel_is_refused_with_its_place() {
    let tmp = tempfile::tempdir().unwrap();
    let (_, npy) = small(tmp.path());
    let mut a = physvid_shared::npy::read_npy(&npy).unwrap();
    a.data[5 * 20 * 256 + 3 * 256 + 17] = 3e38;
    let hot = tmp.path().join("hot.npy");
    physvid_shared::npy::write_npy(std::fs::File::create(&hot).unwrap(), &a.shape, &a.data)
        .unwrap();
    Estimate::new(&hot)
        .args(["--dt", "0.2", "--model", "damped-oscillator"])
        .out(&tmp.path().join("run"))
        .bad_input("clip 5, frame 3, pixel 17");
}

#[test]
fn a_name_or_a_flag_given_twice_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (data, npy) = small(tmp.path());
    let out = tmp.path().join("run");
    Estimate::new(&data)
        .args(["--init", "gamma0=1,gamma0=2"])
        .out(&out)
        .bad_input("'gamma0' is given twice");
    Estimate::new(&data)
        .args(["--init", "gamma0=1", "--init", "gamma1=0.2"])
        .out(&out)
        .bad_input("--init");
    Estimate::new(&npy)
        .args(["--dt", "0.2", "--model", "torricelli"])
        .args([
            "--reference",
            "0:0=0.05,1:2=0.02",
            "--reference",
            "2:2=0.03",
        ])
        .out(&out)
        .bad_input("--reference");
}

/// `data` with its meta.json's calibration changed by `f`.
fn with_calibration(data: &str, f: impl Fn(&mut serde_json::Value)) {
    let path = Path::new(data).join("meta.json");
    let mut meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    f(&mut meta);
    std::fs::write(&path, serde_json::to_string(&meta).unwrap()).unwrap();
}

#[test]
fn impossible_calibrations_are_refused_and_overrides_named() {
    let tmp = tempfile::tempdir().unwrap();
    let block = gen_dataset(
        &tmp.path().join("block"),
        "sliding-block",
        &["--samples", "40", "--size", "16"],
    );
    let out = tmp.path().join("run");
    for (key, value, needle) in [
        (
            "incline_deg",
            serde_json::json!(0.0),
            "calibration.incline_deg",
        ),
        (
            "incline_deg",
            serde_json::json!(90.0),
            "calibration.incline_deg",
        ),
        (
            "incline_deg",
            serde_json::json!(-5.0),
            "calibration.incline_deg",
        ),
        ("g", serde_json::json!(0.0), "calibration.g"),
        ("g", serde_json::json!(1e308), "calibration.g"),
    ] {
        let copy = tmp.path().join(format!("copy-{key}-{value}"));
        copy_dir(Path::new(&block), &copy);
        with_calibration(copy.to_str().unwrap(), |m| {
            m["calibration"][key] = value.clone()
        });
        Estimate::new(&copy).out(&out).bad_input(needle);
    }
    let copy = tmp.path().join("late");
    copy_dir(Path::new(&block), &copy);
    with_calibration(copy.to_str().unwrap(), |m| {
        m["clip_start_times"][0] = serde_json::json!(1e300)
    });
    Estimate::new(&copy)
        .out(&out)
        .bad_input("clip_start_times[0]");
    Estimate::new(&block)
        .args(["--g", "1e308"])
        .out(&out)
        .bad_input("--g 1e308");
    // A flag that overrides meta.json is reported as the source.
    Estimate::new(&block)
        .args(["--incline-deg", "20", "--epochs", "2"])
        .out(&out)
        .quiet()
        .estimated();
    assert_eq!(
        read_report(&out)["calibration"]["incline_source"],
        "--incline-deg"
    );
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn inputs_that_would_block_and_unbounded_work_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (data, _) = small(tmp.path());
    let out = tmp.path().join("run");
    #[cfg(unix)]
    for name in ["pipe.npy", "pipe.mp4", "pipe.toml"] {
        let fifo = tmp.path().join(name);
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let cmd = if name.ends_with("toml") {
            Estimate::new(&data).arg("--model").arg(&fifo)
        } else {
            Estimate::new(&fifo).args(["--dt", "0.2", "--model", "led"])
        };
        cmd.out(&out).bad_input("FIFO");
    }
    Estimate::new(&data)
        .args(["--ensemble", "1000"])
        .out(&out)
        .bad_input("--ensemble 1000");
    Estimate::new(&data)
        .args(["--epochs", "1000000000"])
        .out(&out)
        .bad_input("--epochs");
}

#[test]
fn no_estimate_leaves_no_earlier_report() {
    let tmp = tempfile::tempdir().unwrap();
    // A run that gives no estimate (exit 3) leaves no earlier report.json behind.
    let (_, npy) = small(tmp.path());
    let out = tmp.path().join("run");
    let osc = || {
        Estimate::new(&npy)
            .args([
                "--dt",
                "0.2",
                "--model",
                "damped-oscillator",
                "--epochs",
                "2",
            ])
            .out(&out)
            .quiet()
    };
    osc().estimated();
    assert!(out.join("report.json").exists());
    let o = osc()
        .args(["--single-start", "--init", "gamma1=1e14"])
        .output();
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(!out.join("report.json").exists());
}

#[test]
fn a_picture_of_one_pixel_is_not_graded_ok() {
    let tmp = tempfile::tempdir().unwrap();
    let (_, npy) = small(tmp.path());
    let a = physvid_shared::npy::read_npy(&npy).unwrap();
    let [n, t] = [a.shape[0], a.shape[1]];
    let px = 16 * 16;
    let means: Vec<f32> = a
        .data
        .chunks(px)
        .map(|f| f.iter().sum::<f32>() / px as f32)
        .collect();
    let tiny = tmp.path().join("tiny.npy");
    physvid_shared::npy::write_npy(
        std::fs::File::create(&tiny).unwrap(),
        &[n, t, 1, 1, 1],
        &means,
    )
    .unwrap();
    let out = tmp.path().join("run");
    Estimate::new(&tiny)
        .args([
            "--dt",
            "0.2",
            "--model",
            "damped-oscillator",
            "--threads",
            "2",
        ])
        .out(&out)
        .quiet()
        .estimated();
    assert_ne!(read_report(&out)["verdict"]["grade"], "ok");
}

#[test]
fn a_model_without_oscillation_is_not_judged_as_one() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("fall.toml");
    std::fs::write(
        &file,
        "name = \"myfall\"\n[parameters]\na = { start = 1.0 }\n[state]\nx = \"v\"\nv = \"a\"\n\
         [observed]\nlatent = [\"x\"]\n[initial]\nx = [0.0, 1.0]\nv = [0.0, 1.0]\n",
    )
    .unwrap();
    let data = gen_dataset(
        &tmp.path().join("set"),
        "position",
        &[
            "--model",
            file.to_str().unwrap(),
            "--samples",
            "60",
            "--size",
            "16",
        ],
    );
    let out = tmp.path().join("run");
    Estimate::new(&data)
        .arg("--model")
        .arg(&file)
        .args(["--threads", "2"])
        .out(&out)
        .quiet()
        .estimated();
    let reasons = read_report(&out)["verdict"]["reasons"].to_string();
    assert!(!reasons.contains("oscillation"), "{reasons}");
}

/// The first 200 frames of `data` as a 10-fps video with ffmpeg's `filters` and keyframes
/// every 40 frames.
fn video_of(data: &str, video: &Path, filters: &[&str]) {
    let a = physvid_shared::npy::read_npy(&Path::new(data).join("frames.npy")).unwrap();
    let frames: Vec<u8> = a.data[..200 * 256]
        .iter()
        .map(|v| (v * 255.0).round() as u8)
        .collect();
    let mut child = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "gray"])
        .args(["-s", "16x16", "-r", "10", "-i", "-"])
        .args(filters)
        .args([
            "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "10", "-g", "40",
        ])
        .arg(video)
        .stdin(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child.stdin.take().unwrap().write_all(&frames).unwrap();
    assert!(child.wait().unwrap().success());
}

/// `estimate VIDEO` on 16×16 frames at stride 1 into `out`.
fn on_video(video: &Path, out: &Path) -> util::TestCommand {
    Estimate::new(video)
        .args(["--model", "damped-oscillator", "--size", "16x16"])
        .args(["--stride", "1"])
        .out(out)
}

#[test]
fn uneven_frame_times_are_refused_not_read_as_even() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let (data, _) = small(tmp.path());
    // Frames 40–59 dropped (their time kept).
    let video = tmp.path().join("gap.mp4");
    let drop = ["-vf", "select='not(between(n,40,59))'", "-fps_mode", "vfr"];
    video_of(&data, &video, &drop);
    let out = tmp.path().join("run");
    on_video(&video, &out).bad_input("not evenly spaced");
    // The part before the gap is even.
    on_video(&video, &out)
        .args(["--end", "3.8", "--epochs", "2"])
        .quiet()
        .estimated();
}

#[test]
fn a_healthy_file_whose_container_holds_frames_it_never_shows_is_read() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let (data, _) = small(tmp.path());
    // Trimmed without re-encoding (an edit list, as phones trim): the container holds the
    // frames from the keyframe before the cut, which are decoded but never shown, so its
    // header and index announce more frames than a player presents.
    let (full, trimmed) = (tmp.path().join("full.mp4"), tmp.path().join("trim.mp4"));
    video_of(&data, &full, &[]);
    let status = std::process::Command::new("ffmpeg")
        .args(["-v", "error", "-y", "-ss", "7", "-i"])
        .arg(&full)
        .args(["-c", "copy"])
        .arg(&trimmed)
        .status()
        .unwrap();
    assert!(status.success());
    let out = tmp.path().join("run");
    on_video(&trimmed, &out)
        .args(["--epochs", "2"])
        .quiet()
        .estimated();
    let decoded = read_report(&out)["recording"]["frames_decoded"]
        .as_u64()
        .unwrap();
    assert_eq!(decoded, 130, "the 13 s after the cut at 10 fps");
}
