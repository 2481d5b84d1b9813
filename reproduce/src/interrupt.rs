//! A run stopped by a signal (Ctrl-C, SIGTERM, SIGHUP) cleans up after itself: its workers are
//! stopped and the scratch directory it made for its datasets (gigabytes for `all`) is removed
//! before it exits with 128 + the signal's number. (A `--scratch` the user named is kept, as it
//! is after a run that ends: no handler then, and the workers end with their parent.)

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Duration;

/// The worker processes running now (`--jobs`), by id.
static WORKERS: Mutex<Vec<u32>> = Mutex::new(Vec::new());

/// Notes that worker `pid` runs, until [`ended`].
pub fn started(pid: u32) {
    WORKERS.lock().unwrap_or_else(|e| e.into_inner()).push(pid);
}

/// Notes that worker `pid` ended.
pub fn ended(pid: u32) {
    WORKERS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|p| *p != pid);
}

/// From now on a signal stops the workers, removes `scratch` and ends the process.
pub fn remove_on_signal(scratch: PathBuf) -> std::io::Result<()> {
    let mut signals = Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::spawn(move || {
        let Some(signal) = signals.forever().next() else {
            return;
        };
        let workers = WORKERS.lock().unwrap_or_else(|e| e.into_inner()).clone();
        for pid in workers {
            // SAFETY: kill has no memory effects; a worker already gone makes it fail harmlessly.
            unsafe {
                libc::kill(pid as libc::pid_t, libc::SIGTERM);
            }
        }
        remove(&scratch);
        eprintln!(
            "reproduce: stopped by signal {signal}; removed the scratch directory {}",
            scratch.display()
        );
        std::process::exit(128 + signal);
    });
    Ok(())
}

/// Removes `dir`, trying again for a second while a worker or the estimation in this process
/// may still add files to it.
fn remove(dir: &std::path::Path) {
    for _ in 0..20 {
        match std::fs::remove_dir_all(dir) {
            Ok(()) => return,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return,
            Err(_) => std::thread::sleep(Duration::from_millis(50)),
        }
    }
}
