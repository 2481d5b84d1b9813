//! Issue 50's classes about what the tool writes, tried as a hostile user would: a user's
//! folder under --out (data loss), links planted where the tool writes, and text from files
//! that reaches a spreadsheet, a page or a terminal (injection). Each test fails on the code
//! before the issue. (What is left when a run fails: hostile_leftovers.rs; `gen`'s classes:
//! generator/tests/hostile_gen.rs.)

mod util;

use std::path::Path;
use util::{
    batch, folder_run, gen_dataset, need_ffmpeg, read_report, stderr, write_frames, Estimate,
    TestCommand,
};

/// Every name a run, a batch or a data set writes, and a note of the user's.
fn names() -> Vec<&'static str> {
    let mut v = estimator::output::OUTPUTS.to_vec();
    v.extend(estimator::batch::SUMMARY_FILES);
    v.extend(physvid_shared::dataset::DATASET_FILES);
    v.push("notes.txt");
    v
}

/// A small intensity set (40 clips of 16×16).
fn small_set(dir: &Path) -> String {
    gen_dataset(dir, "intensity", &["--samples", "40", "--size", "16"])
}

/// `estimate SET` for two epochs.
fn quick(set: &str) -> TestCommand {
    Estimate::new(set).args(["--epochs", "2", "--quiet"])
}

/// Every entry of `dir` with its bytes (a folder's as empty), sorted.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let bytes = std::fs::read(e.path()).unwrap_or_default();
            (e.file_name().to_string_lossy().into_owned(), bytes)
        })
        .collect();
    v.sort();
    v
}

#[test]
fn a_users_folder_survives_every_command_byte_for_byte() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let home = tmp.path().join("home");
    std::fs::create_dir(&home).unwrap();
    for name in names() {
        std::fs::write(home.join(name), format!("the user's {name}")).unwrap();
    }
    let before = snapshot(&home);
    let batch_file = tmp.path().join("runs.csv");
    std::fs::write(&batch_file, format!("input\n{set}\n")).unwrap();
    let batch_out = tmp.path().join("batch");
    let o = batch(&batch_file, &batch_out, "2").output();
    assert!(batch_out.join("summary.json").exists(), "{}", stderr(&o));
    let refusals: Vec<TestCommand> = vec![
        quick(&set).out(&home),
        // `--out .` from inside the folder.
        quick(&set).arg("--out").arg(".").current_dir(&home),
        // A run that would end without an estimate (exit 3) is refused before it starts.
        quick(&set)
            .args(["--single-start", "--init", "gamma1=1e14"])
            .out(&home),
        Estimate::bare()
            .arg("--batch")
            .arg(&batch_file)
            .out(&home)
            .quiet(),
        Estimate::bare().arg("--merge").arg(&batch_out).out(&home),
    ];
    for cmd in refusals {
        let o = cmd.output();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert_eq!(snapshot(&home), before, "{}", stderr(&o));
    }
    let o = quick(&set).out(&home).output();
    assert!(
        stderr(&o).contains("did not write") && stderr(&o).contains("--force"),
        "the refusal says why and how: {}",
        stderr(&o)
    );
    // --force writes the run's files beside the user's: nothing of another name changes.
    quick(&set).out(&home).arg("--force").estimated();
    let after = snapshot(&home);
    for (name, bytes) in &before {
        // A data set's run writes the first five of its outputs (no recording's).
        let run_writes = &estimator::output::OUTPUTS[..5];
        if !run_writes.contains(&name.as_str()) {
            let now = after.iter().find(|(n, _)| n == name).map(|(_, b)| b);
            assert_eq!(now, Some(bytes), "{name} changed");
        }
    }
}

#[test]
fn only_the_tools_own_files_are_ever_removed_or_replaced() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let out = tmp.path().join("run");
    quick(&set).out(&out).estimated();
    // The user edits a file the tool wrote: the next run refuses rather than replace it.
    let edited = out.join("metrics.csv");
    let mut text = std::fs::read_to_string(&edited).unwrap();
    text += "my note\n";
    std::fs::write(&edited, &text).unwrap();
    quick(&set).out(&out).bad_input("did not write that file");
    assert_eq!(std::fs::read_to_string(&edited).unwrap(), text);
    // A note of another name in the tool's folder is left alone, by a run that gives no
    // estimate too (exit 3), which removes the tool's earlier report.
    std::fs::remove_file(&edited).unwrap();
    std::fs::write(out.join("notes.txt"), b"mine").unwrap();
    let o = quick(&set)
        .args(["--single-start", "--init", "gamma1=1e14"])
        .out(&out)
        .output();
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(
        !out.join("report.json").exists(),
        "no earlier report stands"
    );
    assert_eq!(std::fs::read(out.join("notes.txt")).unwrap(), b"mine");
    quick(&set).out(&out).estimated();
    assert!(read_report(&out)["parameters"].is_array());
}

#[test]
fn the_output_is_never_read_back_as_input() {
    if !need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let frames = tmp.path().join("frames");
    write_frames(&frames, 60);
    let run = |out: &Path| folder_run(&frames).out(out).quiet();
    run(&frames).bad_input("the input folder itself");
    assert!(!frames.join("report.json").exists());
    // A folder of the tool's plots is not a recording.
    let out = tmp.path().join("run");
    run(&out).estimated();
    Estimate::new(&out)
        .args(["--fps", "10", "--model", "damped-oscillator"])
        .out(&tmp.path().join("again"))
        .bad_input("this tool's outputs");
}

/// The pid the next process will probably get (Linux), for planting links at names a tool
/// derives from its pid.
fn next_pids() -> std::ops::Range<u32> {
    let last: u32 = std::fs::read_to_string("/proc/sys/kernel/ns_last_pid")
        .ok()
        .and_then(|t| t.trim().parse().ok())
        .unwrap_or(1);
    last + 1..last + 400
}

#[cfg(target_os = "linux")]
#[test]
fn links_planted_where_the_tool_writes_are_never_written_through() {
    use std::os::unix::fs::symlink;
    let tmp = tempfile::tempdir().unwrap();
    let victim = tmp.path().join("victim");
    std::fs::write(&victim, b"precious").unwrap();
    let set = small_set(&tmp.path().join("set"));
    // A run's folder from an earlier run, with links at its names and at the temporary and
    // lock names the tool once used.
    let out = tmp.path().join("run");
    quick(&set).out(&out).estimated();
    for name in [
        "report.json",
        "report.json.partial",
        "metrics.csv.partial",
        ".lock",
    ] {
        let _ = std::fs::remove_file(out.join(name));
        symlink(&victim, out.join(name)).unwrap();
    }
    quick(&set).out(&out).bad_input("link");
    quick(&set).out(&out).arg("--force").estimated();
    assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
    assert!(!out.join("report.json").is_symlink());
    // A batch row's folder planted as a link to somewhere else: the batch is refused.
    let elsewhere = tmp.path().join("elsewhere");
    std::fs::create_dir(&elsewhere).unwrap();
    let batch_file = tmp.path().join("runs.csv");
    std::fs::write(&batch_file, format!("input,name\n{set},a\n{set},b\n")).unwrap();
    let batch_out = tmp.path().join("batch");
    let o = batch(&batch_file, &batch_out, "2").output();
    assert!(batch_out.join("01-a").is_dir(), "{}", stderr(&o));
    std::fs::remove_dir_all(batch_out.join("01-a")).unwrap();
    symlink(&elsewhere, batch_out.join("01-a")).unwrap();
    batch(&batch_file, &batch_out, "2").bad_input("link");
    assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
    // The image folder's frame list in a shared temporary folder: links at the names a pid
    // would give.
    if !need_ffmpeg() {
        return;
    }
    let shared_tmp = tmp.path().join("tmp");
    std::fs::create_dir(&shared_tmp).unwrap();
    for pid in next_pids() {
        let _ = symlink(
            &victim,
            shared_tmp.join(format!("physvid-frames-{pid}-0.ffconcat")),
        );
    }
    let frames = tmp.path().join("frames");
    write_frames(&frames, 60);
    folder_run(&frames)
        .out(&tmp.path().join("folder-run"))
        .quiet()
        .env("TMPDIR", &shared_tmp)
        .estimated();
    assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
}

#[test]
fn text_from_files_reaches_spreadsheets_pages_and_terminals_as_text() {
    let tmp = tempfile::tempdir().unwrap();
    let set = small_set(&tmp.path().join("set"));
    let batch_file = tmp.path().join("runs.csv");
    std::fs::write(
        &batch_file,
        format!(
            "input,name\n{set},\"=HYPERLINK(\"\"http://x\"\")\"\n@missing.npy,\"<img src=x onerror=alert(1)>|x\"\n"
        ),
    )
    .unwrap();
    let out = tmp.path().join("batch");
    let o = batch(&batch_file, &out, "2").output();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    for record in reader.records() {
        for cell in record.unwrap().iter() {
            assert!(!cell.starts_with(['=', '+', '@']), "a formula cell: {cell}");
        }
    }
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(!md.contains("<img"), "{md}");
    // An escape sequence in a file name and in a model's unit reaches the terminal escaped.
    let odd = tmp.path().join("set\u{1b}[31m");
    std::fs::rename(tmp.path().join("set"), &odd).unwrap();
    let model = tmp.path().join("odd.toml");
    std::fs::write(
        &model,
        "name = \"odd\"\n[parameters]\ngamma0 = { start = 1.0, positive = true, unit = \"1/s\\u001b[2J\" }\n\
         gamma1 = { start = 0.1 }\n[state]\nx = \"v\"\nv = \"-gamma0*x - gamma1*v\"\n\
         [observed]\nlatent = [\"x\"]\n[initial]\nx = [0.5, 1.0]\nv = [-1.0, 1.0]\n",
    )
    .unwrap();
    let o = Estimate::new(&odd)
        .args(["--epochs", "2", "--model"])
        .arg(&model)
        .out(&tmp.path().join("odd-run"))
        .output();
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", stderr(&o));
    let all = [&o.stdout[..], &o.stderr[..]].concat();
    assert!(!all.contains(&0x1b), "{}", String::from_utf8_lossy(&all));
    assert!(String::from_utf8_lossy(&o.stdout).contains("\\x1b[2J"));
    // A newline in a file name: the refusal stays one line.
    Estimate::new(tmp.path().join("two\nlines.npy"))
        .args(["--dt", "0.2"])
        .out(&tmp.path().join("nl"))
        .bad_input("two\\nlines.npy");
}
