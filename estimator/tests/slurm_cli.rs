//! `estimate --batch` under a real Slurm: `examples/batch.sbatch` (the recipe of
//! docs/recordings.md) submitted as a job array to a one-node cluster started here
//! (`scripts/slurm.sh`), its shards merged, equal to the batch run whole. Needs Debian's
//! slurmctld, slurmd and slurm-client and root (skipped with a message otherwise; failing
//! under CI=true).

mod util;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use util::{bin, gen_dataset, stderr, without_wall, Estimate};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn found(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// A cluster started in `dir`, stopped when dropped.
struct Cluster {
    dir: PathBuf,
}

impl Cluster {
    fn start(dir: &Path) -> Cluster {
        let o = Command::new(repo().join("scripts/slurm.sh"))
            .arg("start")
            .arg(dir)
            .output()
            .unwrap();
        let cluster = Cluster {
            dir: dir.to_path_buf(),
        };
        assert!(o.status.success(), "slurm.sh start: {}", stderr(&o));
        cluster
    }

    fn command(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", self.dir.join("slurm.conf"));
        c
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = Command::new(repo().join("scripts/slurm.sh"))
            .arg("stop")
            .arg(&self.dir)
            .output();
    }
}

#[test]
fn a_job_array_of_shards_merges_to_the_batch_run_whole() {
    let root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0");
    let have = ["slurmctld", "slurmd", "sbatch", "squeue"]
        .iter()
        .all(|p| found(p));
    if !physvid_testkit::require(
        "Slurm (slurmctld, slurmd, sbatch) run as root",
        have && root,
        "a one-node cluster for the job-array batch",
    ) {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    for (name, scenario) in [("a", "intensity"), ("b", "scale"), ("c", "position")] {
        gen_dataset(
            &tmp.path().join("sets").join(name),
            scenario,
            &["--samples", "60", "--size", "32", "--seed", "4"],
        );
    }
    let runs = tmp.path().join("runs.csv");
    std::fs::write(&runs, "input,name\nsets/a,\nsets/b,\nsets/c,\n").unwrap();
    let flags = ["--epochs", "3", "--quiet"];

    let cluster = Cluster::start(&tmp.path().join("slurm"));
    // The job inherits this PATH, with `estimate` on it, as the recipe asks.
    let path = format!(
        "{}:{}",
        bin().parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = cluster
        .command("sbatch")
        .env("PATH", &path)
        .current_dir(tmp.path())
        .args(["--parsable", "--array=1-2", "--output=job-%a.txt"])
        .arg(repo().join("examples/batch.sbatch"))
        .args(["runs.csv", "lab"])
        .args(flags)
        .output()
        .unwrap();
    assert!(o.status.success(), "sbatch: {}", stderr(&o));
    let job = String::from_utf8_lossy(&o.stdout).trim().to_string();
    let begun = Instant::now();
    loop {
        let q = cluster
            .command("squeue")
            .args(["-h", "-j", &job])
            .output()
            .unwrap();
        if q.status.success() && q.stdout.iter().all(|b| b.is_ascii_whitespace()) {
            break;
        }
        assert!(
            begun.elapsed() < Duration::from_secs(300),
            "job {job} still queued"
        );
        std::thread::sleep(Duration::from_millis(250));
    }
    drop(cluster);
    let log = |i: usize| std::fs::read_to_string(tmp.path().join(format!("job-{i}.txt")));
    for i in 1..=2 {
        assert!(
            tmp.path()
                .join(format!("lab/shard-{i}/summary.csv"))
                .is_file(),
            "task {i}: {:?}",
            log(i)
        );
    }
    let merged = tmp.path().join("lab/all");
    let o = Estimate::bare()
        .arg("--merge")
        .arg(tmp.path().join("lab/shard-1"))
        .arg(tmp.path().join("lab/shard-2"))
        .out(&merged)
        .output();
    let whole = tmp.path().join("whole");
    let w = Estimate::bare()
        .arg("--batch")
        .arg(&runs)
        .out(&whole)
        .args(flags)
        .args(["--threads", "1"])
        .output();
    // Three epochs leave some rows unreliable (exit code 1 for both, the same rows).
    assert_eq!(
        o.status.code(),
        w.status.code(),
        "{}\n{}",
        stderr(&o),
        stderr(&w)
    );
    let read = |d: &Path| std::fs::read_to_string(d.join("summary.csv")).unwrap();
    let (merged, whole) = (read(&merged), read(&whole));
    assert_eq!(merged.lines().count(), 4, "{merged}");
    assert_eq!(without_wall(&merged), without_wall(&whole));
}
