//! A one-node Slurm cluster for end-to-end tests (`scripts/slurm.sh` starts it in a folder),
//! stopped when dropped: job arrays submitted with `sbatch` and waited for with `squeue`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// The repository's root (testkit lives one level below it).
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn found(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Whether Slurm can run here (its programs installed, and root to start the daemons); says
/// why not, and fails under CI=true (`crate::require`).
pub fn available() -> bool {
    let root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0");
    let programs = ["slurmctld", "slurmd", "sbatch", "squeue"]
        .iter()
        .all(|p| found(p));
    crate::require(
        "Slurm (slurmctld, slurmd, sbatch) run as root",
        programs && root,
        "a one-node cluster for the job-array tests",
    )
}

/// A cluster whose configuration, state and logs are in `dir`.
pub struct Cluster {
    dir: PathBuf,
}

impl Cluster {
    /// Starts one in `dir` and waits until its node takes jobs.
    pub fn start(dir: &Path) -> Cluster {
        let o = Command::new(repo().join("scripts/slurm.sh"))
            .arg("start")
            .arg(dir)
            .output()
            .expect("scripts/slurm.sh runs");
        let cluster = Cluster {
            dir: dir.to_path_buf(),
        };
        assert!(o.status.success(), "slurm.sh start: {}", crate::stderr(&o));
        cluster
    }

    /// `program` (sbatch, squeue, …) talking to this cluster.
    pub fn command(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", self.dir.join("slurm.conf"));
        c
    }

    /// Submits `script ARGS...` as a job array of tasks 1..=`tasks` from `cwd`, with `bin`'s
    /// folder first on the job's PATH (the scripts call the binaries by name), each task's
    /// output in `cwd/job-TASK.txt`; returns the job's id.
    pub fn submit_array(
        &self,
        cwd: &Path,
        tasks: usize,
        bin: &Path,
        script: &Path,
        args: &[&str],
    ) -> String {
        let folder = bin.parent().expect("a binary's folder");
        let path = format!(
            "{}:{}",
            folder.display(),
            std::env::var("PATH").unwrap_or_default()
        );
        let o = self
            .command("sbatch")
            .env("PATH", path)
            .current_dir(cwd)
            .arg("--parsable")
            .arg(format!("--array=1-{tasks}"))
            .arg("--output=job-%a.txt")
            .arg(script)
            .args(args)
            .output()
            .expect("sbatch runs");
        assert!(o.status.success(), "sbatch: {}", crate::stderr(&o));
        String::from_utf8_lossy(&o.stdout).trim().to_string()
    }

    /// Waits until `job` has left the queue (at most `limit`).
    pub fn wait(&self, job: &str, limit: Duration) {
        let begun = Instant::now();
        loop {
            let q = self
                .command("squeue")
                .args(["-h", "-j", job])
                .output()
                .expect("squeue runs");
            if q.status.success() && q.stdout.iter().all(|b| b.is_ascii_whitespace()) {
                return;
            }
            assert!(begun.elapsed() < limit, "job {job} still queued");
            std::thread::sleep(Duration::from_millis(250));
        }
    }

    /// The repository's root, for its scripts.
    pub fn repo() -> PathBuf {
        repo()
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
