//! `reproduce real`: the verdict on the shared real recordings, every candidate's answer judged
//! right or wrong against the recording's known value, and the rates said.

mod util;

use std::collections::HashMap;
use std::path::Path;
use util::{markdown, num, reproduce_quick_with};

/// The fields of a CSV line, quotes honoured (an answer holds commas).
fn fields(line: &str) -> Vec<String> {
    let (mut out, mut cur, mut quoted) = (Vec::new(), String::new(), false);
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cur)),
            c => cur.push(c),
        }
    }
    out.push(cur);
    out
}

/// `reproduce real --quick` on the shared recordings (the pendulum and the negative control):
/// every candidate judged against the known value; the pendulum's chosen answer right and
/// graded ok, every answer on the tree wrong and none graded ok; the rates said. Where the
/// recordings (or ffmpeg) are absent, the table says so and has no rows.
#[test]
fn the_real_table_judges_every_candidate_on_the_shared_recordings() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/real-videos");
    let ffmpeg = std::process::Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success());
    let present = ffmpeg && dir.join("pendulum-redapple.mov").exists();
    let recordings = if present {
        dir.clone()
    } else {
        eprintln!("SKIPPED in part: the shared recordings or ffmpeg are absent");
        tmp.path().join("none")
    };
    reproduce_quick_with(
        "real",
        tmp.path(),
        &["--recordings", recordings.to_str().unwrap()],
    );
    let md = markdown(tmp.path(), "real");
    let text = std::fs::read_to_string(tmp.path().join("real.csv")).unwrap();
    let mut lines = text.lines();
    let header = fields(lines.next().unwrap());
    let rows: Vec<HashMap<String, String>> = lines
        .map(|l| header.iter().cloned().zip(fields(l)).collect())
        .collect();
    if !present {
        assert!(rows.is_empty() && md.contains("were not found"), "{md}");
        return;
    }
    let chosen = rows
        .iter()
        .find(|r| r["recording"] == "pendulum-redapple.mov" && r["chosen"] == "yes")
        .expect("the pendulum's chosen answer");
    assert_eq!(
        (chosen["right"].as_str(), chosen["grade"].as_str()),
        ("yes", "ok"),
        "{chosen:?}"
    );
    assert!(num(chosen, "error").abs() < 0.02, "{chosen:?}");
    let tree: Vec<_> = rows
        .iter()
        .filter(|r| r["recording"] == "negative-tree.mov")
        .collect();
    assert!(!tree.is_empty());
    assert!(
        tree.iter()
            .all(|r| r["right"] == "no" && r["grade"] != "ok"),
        "{tree:?}"
    );
    assert!(
        md.contains("detection") && md.contains("false alarms"),
        "{md}"
    );
}
