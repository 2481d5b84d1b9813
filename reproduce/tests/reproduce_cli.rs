//! End-to-end tests of `reproduce --quick`: each table regenerates from nothing, writes both
//! files, and shows the paper's qualitative findings (MSE only collapses; the exact block is
//! within 1 % at every dt while Euler's γ0 falls with dt); same seed, same numbers; bad flags
//! get one line and exit code 2.

mod util;

use physvid_testkit::stderr;
use util::{
    markdown, num, read_csv, reproduce, reproduce_quick, reproduce_quick_with, rows_without_wall,
};

#[test]
fn table3_mse_only_collapses_and_mse_kl_recovers_gamma0() {
    let tmp = tempfile::tempdir().unwrap();
    reproduce_quick("table3", tmp.path());
    let rows = read_csv(tmp.path(), "table3");
    assert_eq!(rows.len(), 4);
    let row = |loss: &str, integ: &str| {
        rows.iter()
            .find(|r| r["loss"] == loss && r["integrator"] == integ)
            .unwrap_or_else(|| panic!("no row {loss} {integ}"))
    };
    for integ in ["exact", "euler"] {
        let (kl, mse) = (row("mse+kl", integ), row("mse", integ));
        assert!(
            num(mse, "latent_std") < 0.3 * num(kl, "latent_std"),
            "{integ}: MSE-only latent std {} vs {}",
            mse["latent_std"],
            kl["latent_std"]
        );
        assert!(
            num(mse, "gamma0_rel_error").abs() > 0.1 || num(mse, "gamma1_rel_error").abs() > 0.5,
            "{integ}: MSE only should miss the truth: {mse:?}"
        );
        assert_eq!(num(kl, "gamma0_paper"), 3.99);
        assert_eq!(num(mse, "gamma1_paper"), 6.6);
    }
    assert!(num(row("mse+kl", "exact"), "gamma0_rel_error").abs() < 0.01);
    let md = markdown(tmp.path(), "table3");
    assert!(md.contains("| γ0 paper |"), "{md}");
    assert!(
        md.contains("Made by `reproduce table3 --quick --threads 2`"),
        "{md}"
    );
}

#[test]
fn table6_exact_is_within_1_percent_at_every_dt_and_euler_gamma0_falls_with_dt() {
    let tmp = tempfile::tempdir().unwrap();
    reproduce_quick("table6", tmp.path());
    let rows = read_csv(tmp.path(), "table6");
    // Intensity γ1 and γ0, Torricelli k, pendulum L: 3 dt × 2 integrators each.
    assert_eq!(rows.len(), 24);
    let gamma0: Vec<_> = rows
        .iter()
        .filter(|r| r["scenario"] == "intensity" && r["parameter"] == "γ0")
        .collect();
    let mut euler = Vec::new();
    for r in &gamma0 {
        match r["integrator"].as_str() {
            "exact" => assert!(
                num(r, "rel_error").abs() < 0.01,
                "exact γ0 at dt {}: {}",
                r["dt"],
                r["estimate"]
            ),
            _ => {
                // The paper's block lands on the value the Euler step needs (paper-notes).
                let fixed = num(r, "euler_fixed_point");
                assert!((num(r, "estimate") - fixed).abs() < 0.01 * fixed, "{r:?}");
                euler.push((num(r, "dt"), num(r, "estimate")));
            }
        }
    }
    euler.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(euler.len(), 3);
    assert!(
        euler[0].1 > euler[1].1 && euler[1].1 > euler[2].1,
        "Euler γ0 should fall with dt: {euler:?}"
    );
    assert!(euler[2].1 < 0.9 * 4.0016, "{euler:?}");
    let md = markdown(tmp.path(), "table6");
    assert!(md.contains("Euler fixed point"), "{md}");
}

#[test]
fn the_other_tables_write_their_rows() {
    let tmp = tempfile::tempdir().unwrap();
    for (table, rows_expected) in [("init", 12), ("losses", 6), ("noise", 6), ("coverage", 4)] {
        reproduce_quick(table, tmp.path());
        let rows = read_csv(tmp.path(), table);
        assert_eq!(rows.len(), rows_expected, "{table}");
        assert!(markdown(tmp.path(), table).contains(&format!("reproduce {table} --quick")));
    }
    // Our loss on the clean intensity set, and the noise-free row of the noise table.
    let losses = read_csv(tmp.path(), "losses");
    let ours = losses
        .iter()
        .find(|r| r["scenario"] == "intensity" && r["loss"] == "mse+kl")
        .unwrap();
    assert!(num(ours, "gamma0_rel_error").abs() < 0.01, "{ours:?}");
    let noise = read_csv(tmp.path(), "noise");
    assert_eq!(num(&noise[0], "noise"), 0.0);
    assert!(
        num(&noise[0], "gamma0_rel_error").abs() < 0.01,
        "{:?}",
        noise[0]
    );
    // Our two starts find the truth on intensity from every start.
    let init = read_csv(tmp.path(), "init");
    for r in init
        .iter()
        .filter(|r| r["scenario"] == "intensity" && r["mode"].starts_with("ours"))
    {
        assert_eq!(num(r, "successes"), 1.0, "{r:?}");
    }
    let coverage = read_csv(tmp.path(), "coverage");
    assert_eq!(coverage[3]["data_seed"], "covered");
}

/// Twice the same tables, the second time with their runs side by side in processes of their
/// own (`--jobs 2`): the same numbers (the spring's last row reads a data set's bare array).
#[test]
fn same_command_gives_the_same_table_one_run_at_a_time_or_side_by_side() {
    let tmp = tempfile::tempdir().unwrap();
    let strip = rows_without_wall;
    for table in ["losses", "spring"] {
        reproduce_quick(table, &tmp.path().join("a"));
        reproduce_quick_with(table, &tmp.path().join("b"), &["--jobs", "2"]);
        let one_at_a_time = strip(&tmp.path().join("a"), table);
        assert_eq!(one_at_a_time.len(), if table == "spring" { 5 } else { 6 });
        assert_eq!(
            one_at_a_time,
            strip(&tmp.path().join("b"), table),
            "{table}"
        );
    }
}

#[test]
fn reproduce_bad_input_gets_a_one_line_error_and_exit_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("a-file");
    std::fs::write(&file, b"x").unwrap();
    reproduce().arg("table9").bad_input("table9");
    reproduce().arg("table3").out(&file).bad_input("is a file");
    for n in ["0", "100000"] {
        for flag in ["--threads", "--jobs"] {
            reproduce()
                .args(["table3", flag, n])
                .bad_input("must be from 1 to 256");
        }
    }
    let o = reproduce().arg("--help").ok();
    let help = String::from_utf8_lossy(&o.stdout);
    for word in [
        "table3", "table6", "init", "losses", "noise", "coverage", "all", "--quick", "--out",
        "--jobs",
    ] {
        assert!(help.contains(word), "--help lacks {word}");
    }
}

/// A run stopped by SIGTERM midway (its workers running) exits with 143 and leaves no scratch
/// directory in the temporary directory.
#[test]
fn a_run_stopped_by_a_signal_removes_its_scratch_directory() {
    let tmp = tempfile::tempdir().unwrap();
    let temp_root = tmp.path().join("tmp");
    std::fs::create_dir(&temp_root).unwrap();
    let scratch = || -> Vec<std::path::PathBuf> {
        std::fs::read_dir(&temp_root)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .filter(|p| {
                p.file_name()
                    .unwrap()
                    .to_string_lossy()
                    .starts_with("reproduce-")
            })
            .collect()
    };
    let mut child = reproduce()
        .args([
            "spring",
            "--quick",
            "--quiet",
            "--jobs",
            "2",
            "--threads",
            "1",
        ])
        .args(["--device", "cpu"])
        .out(&tmp.path().join("out"))
        .env("TMPDIR", &temp_root)
        .spawn();
    // Wait until a worker writes its run (a `run-N` directory in the scratch directory).
    let start = std::time::Instant::now();
    let running = loop {
        let busy = scratch().iter().any(|d| {
            std::fs::read_dir(d).is_ok_and(|es| {
                es.flatten()
                    .any(|e| e.file_name().to_string_lossy().starts_with("run-"))
            })
        });
        if busy || start.elapsed().as_secs() > 120 || child.try_wait().unwrap().is_some() {
            break busy;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    assert!(running, "no worker ran within 120 s");
    // SAFETY: kill has no memory effects.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGTERM) },
        0
    );
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(143), "{}", stderr(&out));
    assert!(stderr(&out).contains("removed the scratch directory"));
    assert_eq!(scratch(), Vec::<std::path::PathBuf>::new());
}

/// Ctrl-C while an estimation trains in this very process (no workers), with a --scratch the
/// user named: the run ends with 130 at once (it was killed by the signal, or crashed in
/// libtorch's teardown, before) and the named folder stays.
#[test]
fn ctrl_c_while_training_in_process_ends_cleanly() {
    let tmp = tempfile::tempdir().unwrap();
    let scratch = tmp.path().join("scratch");
    let child = reproduce()
        .args(["losses", "--quick", "--quiet", "--threads", "2"])
        .args(["--device", "cpu", "--scratch"])
        .arg(&scratch)
        .out(&tmp.path().join("out"))
        .spawn();
    let start = std::time::Instant::now();
    while std::fs::read_dir(&scratch).map_or(0, |d| d.count()) == 0
        && start.elapsed().as_secs() < 120
    {
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    std::thread::sleep(std::time::Duration::from_millis(1500));
    // SAFETY: kill has no memory effects.
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130), "{}", stderr(&out));
    assert!(scratch.is_dir(), "a --scratch the user named is kept");
}
