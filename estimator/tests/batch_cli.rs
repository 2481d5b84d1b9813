//! End-to-end tests of `estimate --batch`, `--shard` and `--merge`: every row in the summary
//! (failed ones with their error), the exit code, shards merged equal to the whole, and the
//! batch file's bad inputs. The real recordings' rows need `../shared/real-videos` and ffmpeg
//! (skipped with a message otherwise).

mod util;

use std::path::Path;
use util::{gen_dataset, real_video, stderr, without_wall, Estimate};

/// A small synthetic set (100 clips of 32×32).
fn small_set(dir: &Path, scenario: &str) -> String {
    gen_dataset(
        dir,
        scenario,
        &["--samples", "100", "--size", "32", "--seed", "3"],
    )
}

fn batch(file: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    Estimate::bare()
        .arg("--batch")
        .arg(file)
        .out(out)
        .args(["--epochs", "3", "--quiet"])
        .args(extra)
        .output()
}

#[test]
fn a_batch_lists_every_row_fails_with_code_1_and_its_shards_merge_to_the_whole() {
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let videos = video.parent().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    small_set(&tmp.path().join("sets/intensity"), "intensity");
    small_set(&tmp.path().join("sets/scale"), "scale");
    let v = |n: &str| videos.join(n).display().to_string();
    let file = tmp.path().join("runs.csv");
    std::fs::write(
        &file,
        format!(
            "input,name,model,start,end,stride,fps,size,reference,truth\n\
             {},jar,torricelli,3,20,15,,,\"3.0s=0.0727,12.0s=0.0373\",k=0.0170\n\
             {},ball,free-fall,3.933,6.72,,120,16x160,\"3.933s=0,6.7s=2.26\",g=9.81\n\
             {},apple,pendulum,,,,,,,g_over_l=9.15\n\
             sets/intensity,,,,,,,,,\n\
             sets/scale,wrong-model,led,,,,,,,\n",
            v("torricelli-500ml.mp4"),
            v("freefall-ball.mp4"),
            v("pendulum-redapple.mov"),
        ),
    )
    .unwrap();
    let whole = tmp.path().join("whole");
    let o = batch(&file, &whole, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let csv = std::fs::read_to_string(whole.join("summary.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header = reader.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 5, "{csv}");
    let status: Vec<&str> = rows.iter().map(|r| &r[col("status")]).collect();
    // Three epochs are too few for the recordings: a row whose verdict is unreliable (the
    // jar's k came out 5× too large that way) counts as failed, with its estimates listed.
    for r in &rows[..4] {
        let unreliable = &r[col("verdict")] == "unreliable";
        assert_eq!(&r[col("status")] == "unreliable", unreliable, "{csv}");
    }
    assert_eq!(status[3], "ok", "{csv}");
    assert_eq!(status[4], "failed");
    let failed = status.iter().filter(|s| **s != "ok").count();
    assert!(
        stderr(&o).contains(&format!("{failed} of 5 rows failed")),
        "{}",
        stderr(&o)
    );
    // The fifth row fails on purpose: its model contradicts the set's meta.json.
    assert!(
        rows[4][col("error")].contains("--model led contradicts"),
        "{csv}"
    );
    // Units, the known values and their errors; the relative input read from the CSV's folder.
    assert_eq!(&rows[1][col("g_unit")], "m/s^2");
    assert_eq!(&rows[1][col("g_truth")], "9.81");
    assert!(rows[1][col("g_rel_error")].parse::<f64>().is_ok());
    assert_eq!(&rows[3][col("model")], "damped-oscillator");
    for dir in ["01-jar", "02-ball", "03-apple", "04-intensity"] {
        assert!(whole.join(dir).join("report.html").is_file(), "{dir}");
    }
    assert!(!whole.join("05-wrong-model").join("report.json").exists());
    // (minijinja writes '/' in attributes as &#x2f;.)
    let index = std::fs::read_to_string(whole.join("index.html"))
        .unwrap()
        .replace("&#x2f;", "/");
    assert!(index.contains("href=\"03-apple/report.html\""));
    // Two shards, each with its own --out, merged: the same summary.
    let s1 = batch(&file, &tmp.path().join("s1"), &["--shard", "1/2"]);
    assert_eq!(s1.status.code(), Some(1), "row 5 is in shard 1");
    let s2 = batch(&file, &tmp.path().join("s2"), &["--shard", "2/2"]);
    let s2_fails = status[1] != "ok";
    assert_eq!(s2.status.code(), Some(s2_fails as i32), "{}", stderr(&s2));
    let shard1 = std::fs::read_to_string(tmp.path().join("s1/summary.csv")).unwrap();
    assert_eq!(
        shard1.lines().count(),
        4,
        "rows 1, 3, 5 are shard 1's: {shard1}"
    );
    let merged = tmp.path().join("merged");
    let m = Estimate::bare()
        .arg("--merge")
        .arg(tmp.path().join("s1"))
        .arg(tmp.path().join("s2"))
        .out(&merged)
        .arg("--quiet")
        .output();
    assert_eq!(m.status.code(), Some(1), "{}", stderr(&m));
    let merged_csv = std::fs::read_to_string(merged.join("summary.csv")).unwrap();
    assert_eq!(without_wall(&merged_csv), without_wall(&csv));
    let index = std::fs::read_to_string(merged.join("index.html"))
        .unwrap()
        .replace("&#x2f;", "/");
    assert!(
        index.contains("href=\"../s1/03-apple/report.html\""),
        "{index}"
    );
}

#[test]
fn shards_that_miss_rows_merge_with_those_rows_not_run() {
    let tmp = tempfile::tempdir().unwrap();
    small_set(&tmp.path().join("a"), "intensity");
    let file = tmp.path().join("runs.csv");
    std::fs::write(&file, "input,seed\na,1\na,2\na,3\n").unwrap();
    let s1 = batch(&file, &tmp.path().join("s1"), &["--shard", "1/3"]);
    assert_eq!(s1.status.code(), Some(0), "{}", stderr(&s1));
    let o = Estimate::bare()
        .arg("--merge")
        .arg(tmp.path().join("s1"))
        .out(&tmp.path().join("m"))
        .arg("--quiet")
        .output();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let csv = std::fs::read_to_string(tmp.path().join("m/summary.csv")).unwrap();
    let status: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(4).unwrap())
        .collect();
    assert_eq!(status, ["ok", "not run", "not run"], "{csv}");
    // The same directory twice runs its rows twice: refused.
    Estimate::bare()
        .arg("--merge")
        .arg(tmp.path().join("s1"))
        .arg(tmp.path().join("s1"))
        .out(&tmp.path().join("m2"))
        .bad_input("row 1 was run by two");
}

#[test]
fn bad_batch_files_and_flags_are_refused_before_any_row_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("runs.csv");
    let out = tmp.path().join("out");
    std::fs::write(&file, "input,modle\nx.mp4,pendulum\n").unwrap();
    Estimate::bare()
        .arg("--batch")
        .arg(&file)
        .out(&out)
        .bad_input("unknown column 'modle'");
    assert!(!out.join("summary.csv").exists());
    std::fs::write(&file, "input,out\nx.mp4,elsewhere\n").unwrap();
    Estimate::bare()
        .arg("--batch")
        .arg(&file)
        .bad_input("'out' is the batch's own");
    Estimate::bare()
        .arg("--batch")
        .arg(tmp.path().join("none.csv"))
        .bad_input("cannot read it");
    Estimate::bare()
        .args(["--shard", "1/2"])
        .arg(tmp.path())
        .bad_input("--batch");
    Estimate::bare()
        .arg("--batch")
        .arg(&file)
        .args(["--shard", "3/2"])
        .bad_input("I/N");
    Estimate::bare()
        .arg("--merge")
        .arg(tmp.path())
        .out(&out)
        .bad_input("no summary.json");
    Estimate::bare()
        .arg("x.mp4")
        .arg("--batch")
        .arg(&file)
        .bad_input("cannot be used with");
}

#[test]
fn a_missing_file_fails_its_row_only() {
    let tmp = tempfile::tempdir().unwrap();
    small_set(&tmp.path().join("a"), "intensity");
    let file = tmp.path().join("runs.csv");
    std::fs::write(&file, "input,preview\nmissing.mp4,\na,maybe\na,\n").unwrap();
    let out = tmp.path().join("out");
    let o = batch(&file, &out, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows[0]["status"], "failed");
    assert!(
        rows[0]["error"].as_str().unwrap().contains("missing.mp4"),
        "{}",
        rows[0]
    );
    assert_eq!(rows[1]["status"], "failed");
    assert!(rows[1]["error"].as_str().unwrap().contains("true or false"));
    assert_eq!(rows[2]["status"], "ok", "{}", rows[2]);
    assert!(rows[2]["command"].as_str().unwrap().contains("--epochs 3"));
}
