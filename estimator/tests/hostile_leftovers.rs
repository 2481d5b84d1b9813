//! Issue 50's classes about what a failing run leaves and says, tried as a hostile user
//! would: a full disk or a closed pipe, a batch stopped part-way, two batches into one folder,
//! an unusable temporary folder, an image among others of another format, and Ctrl-C midway.
//! Each test fails on the code before the issue.

mod util;

use std::path::{Path, PathBuf};
use util::{
    batch, folder_run, gen_dataset, need_ffmpeg, stderr, write_frames, Estimate, TestCommand,
};

/// A small intensity set (40 clips of 16×16).
fn small_set(dir: &Path) -> String {
    gen_dataset(dir, "intensity", &["--samples", "40", "--size", "16"])
}

/// `estimate SET` for two epochs.
fn quick(set: &str) -> TestCommand {
    Estimate::new(set).args(["--epochs", "2", "--quiet"])
}

/// Files under `dir` (recursively) whose name ends in `.partial`.
fn partial_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let p = e.path();
        if p.is_dir() && !p.is_symlink() {
            found.extend(partial_files(&p));
        } else if p.to_string_lossy().ends_with(".partial") {
            found.push(p);
        }
    }
    found
}

#[test]
fn a_full_disk_or_a_closed_pipe_is_an_error_message_not_a_panic() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let o = quick(&set)
        .out(&tmp.path().join("run"))
        .stdout_to(Path::new("/dev/full"))
        .output();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("standard output"), "{}", stderr(&o));
}

/// `estimate --batch FILE --out OUT` under a file-size limit of `kib` KiB, SIGXFSZ ignored, as
/// a full disk fails a write.
fn batch_on_a_full_disk(file: &Path, out: &Path, kib: u32) -> std::process::Output {
    std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f {kib}; exec \"$0\" --batch \"$1\" --out \"$2\" --epochs 2 --quiet"
        ))
        .arg(util::bin())
        .arg(file)
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn a_batch_stopped_by_a_full_disk_leaves_no_partial_file_and_no_pending_row() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let file = tmp.path().join("runs.csv");
    std::fs::write(&file, format!("input,name\n{set},a\n{set},b\n")).unwrap();
    for kib in [1, 64] {
        let out = tmp.path().join(format!("out-{kib}"));
        let o = batch_on_a_full_disk(&file, &out, kib);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert_eq!(partial_files(&out), Vec::<PathBuf>::new(), "{}", stderr(&o));
        if let Ok(csv) = std::fs::read_to_string(out.join("summary.csv")) {
            assert!(!csv.contains("pending"), "{csv}");
        }
    }
}

#[test]
fn two_batches_never_write_one_folder_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let file = tmp.path().join("runs.csv");
    let rows: String = (0..6).map(|i| format!("{set},r{i}\n")).collect();
    std::fs::write(&file, format!("input,name\n{rows}")).unwrap();
    let out = tmp.path().join("out");
    let mut first = batch(&file, &out, "30").spawn();
    let started = std::time::Instant::now();
    while !out.join("summary.json").exists() && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    batch(&file, &out, "30").bad_input("another run is writing");
    let _ = first.kill();
    let _ = first.wait();
}

#[test]
fn an_unusable_temporary_folder_is_a_failure_not_bad_input() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames(&frames, 40);
    let o = folder_run(&frames)
        .out(&tmp.path().join("run"))
        .env("TMPDIR", tmp.path().join("no-such-folder"))
        .output();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("TMPDIR"), "{}", stderr(&o));
}

#[test]
fn a_jpeg_among_png_frames_is_named() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames(&frames, 30);
    let odd = frames.join("frame12.png");
    image::open(&odd)
        .unwrap()
        .save(frames.join("frame12.jpg"))
        .unwrap();
    std::fs::remove_file(&odd).unwrap();
    Estimate::new(&frames)
        .args(["--fps", "10", "--model", "damped-oscillator"])
        .out(&tmp.path().join("run"))
        .bad_input("frame12.jpg");
}

#[cfg(unix)]
#[test]
fn ctrl_c_ends_a_run_cleanly_and_leaves_nothing_half_made() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let out = tmp.path().join("run");
    let child = Estimate::new(&set)
        .args([
            "--epochs",
            "100000",
            "--patience",
            "100000",
            "--single-start",
        ])
        .out(&out)
        .spawn();
    std::thread::sleep(std::time::Duration::from_millis(2500));
    // SAFETY: kill has no memory effects.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(
        !out.exists(),
        "a folder this run would have made is not left"
    );
    assert_eq!(partial_files(tmp.path()), Vec::<PathBuf>::new());
}
