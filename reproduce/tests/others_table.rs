//! `reproduce others`: footage rendered by others (`scripts/others_suite.py`), each render
//! estimated with no model, judged right or wrong against the suite's truth, the rates said.

mod util;

use util::{markdown, read_csv, reproduce_quick};

/// The quick set: the clean control comes out right and graded ok (it had failed when the clip
/// length chosen by itself spanned a third of a period), the clutter render at level 3 is
/// judged and graded, and the rates are said under the table. Where numpy or ffmpeg is absent
/// the renderer cannot draw: skipped visibly, or a failure under `CI=true`.
#[test]
fn the_others_table_judges_the_clean_control_right_and_ok() {
    let usable = |program: &str, args: &[&str]| {
        std::process::Command::new(program)
            .args(args)
            .output()
            .is_ok_and(|o| o.status.success())
    };
    let venv = concat!(env!("CARGO_MANIFEST_DIR"), "/../.venv/bin/python");
    let python = if std::path::Path::new(venv).exists() {
        venv
    } else {
        "python3"
    };
    let why = "the renderer draws with numpy and writes MP4 with ffmpeg";
    if !physvid_testkit::require("numpy", usable(python, &["-c", "import numpy"]), why)
        || !physvid_testkit::require("ffmpeg", usable("ffmpeg", &["-version"]), why)
    {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    reproduce_quick("others", tmp.path());
    let rows = read_csv(tmp.path(), "others");
    let names: Vec<&str> = rows.iter().map(|r| r["render"].as_str()).collect();
    assert_eq!(names, ["clean", "clutter-3"], "{rows:?}");
    let clean = &rows[0];
    assert_eq!(
        (clean["right"].as_str(), clean["grade"].as_str()),
        ("yes", "ok"),
        "{clean:?}"
    );
    let md = markdown(tmp.path(), "others");
    assert!(
        md.contains("false alarms") && md.contains("detection"),
        "{md}"
    );
}
