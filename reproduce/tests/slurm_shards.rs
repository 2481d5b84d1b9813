//! `reproduce` under a real Slurm: `examples/reproduce.sbatch` submitted as a job array to a
//! one-node cluster started here, each task one shard of a table's estimations, merged into
//! the same table as one run makes (wall times aside); a merge short of a shard refused.
//! Needs Slurm and root (skipped with a message otherwise; failing under CI=true).

mod util;

use physvid_testkit::slurm::{available, Cluster};
use physvid_testkit::stderr;
use std::path::Path;
use std::time::Duration;
use util::{reproduce, rows_without_wall};

#[test]
fn a_table_run_in_shards_of_a_job_array_merges_to_the_table_run_whole() {
    if !available() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let flags = ["--quick", "--quiet", "--device", "cpu"];
    let cluster = Cluster::start(&tmp.path().join("slurm"));
    let bin = Path::new(env!("CARGO_BIN_EXE_reproduce"));
    let script = Cluster::repo().join("examples/reproduce.sbatch");
    let mut args = vec!["losses", "shards"];
    args.extend(flags);
    let job = cluster.submit_array(tmp.path(), 2, bin, &script, &args);
    cluster.wait(&job, Duration::from_secs(600));
    drop(cluster);
    for i in 1..=2 {
        let record = tmp
            .path()
            .join(format!("shards/shard-{i}/losses.shard-{i}-of-2.cbor"));
        let log = std::fs::read_to_string(tmp.path().join(format!("job-{i}.txt")));
        assert!(record.is_file(), "task {i}: {log:?}");
    }
    // Merged (running nothing) against one run with the tasks' two threads.
    let merged = tmp.path().join("merged");
    let o = reproduce()
        .args(["losses", "--merge"])
        .arg(tmp.path().join("shards/shard-1"))
        .arg(tmp.path().join("shards/shard-2"))
        .args(flags)
        .out(&merged)
        .output();
    assert!(o.status.success(), "{}", stderr(&o));
    let whole = tmp.path().join("whole");
    let o = reproduce()
        .arg("losses")
        .args(flags)
        .args(["--threads", "2"])
        .out(&whole)
        .output();
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = |dir: &Path| rows_without_wall(dir, "losses");
    assert_eq!(rows(&whole).len(), 6);
    assert_eq!(rows(&merged), rows(&whole));
    // One shard's folder is not the table.
    let o = reproduce()
        .args(["losses", "--merge"])
        .arg(tmp.path().join("shards/shard-1"))
        .args(flags)
        .out(&tmp.path().join("short"))
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("1 of its 2 shards"), "{}", stderr(&o));
}
