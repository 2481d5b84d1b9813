//! Child processes that end with the thread that started them (Linux's parent-death signal):
//! `estimate --batch`'s rows and `reproduce --jobs`'s workers, whose parent stopped by a
//! signal of its own (not its process group's, as Ctrl-C is) would otherwise leave them
//! running to the end of their estimations.

use std::process::Command;

/// Asks that the process `command` starts get SIGTERM when the thread that starts it ends.
/// The thread must wait for the child (as `output()` does), so it never ends first on its own.
#[cfg(target_os = "linux")]
pub fn die_with_parent(command: &mut Command) {
    use std::os::unix::process::CommandExt;
    let parent = std::process::id() as libc::pid_t;
    // SAFETY: between fork and exec only async-signal-safe calls: prctl, getppid, _exit.
    unsafe {
        command.pre_exec(move || {
            libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM);
            if libc::getppid() != parent {
                libc::_exit(1); // the parent died before the signal was asked for
            }
            Ok(())
        });
    }
}

/// Elsewhere a child outlives a parent stopped alone.
#[cfg(not(target_os = "linux"))]
pub fn die_with_parent(_command: &mut Command) {}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use std::time::{Duration, Instant};

    #[test]
    fn a_child_asked_to_die_with_its_thread_ends_when_the_thread_does() {
        // The thread starts `sleep 30` and ends without waiting for it (what a killed parent
        // amounts to for the signal): the child must be gone well before its 30 s.
        let pid = std::thread::spawn(|| {
            let mut command = Command::new("sleep");
            command.arg("30");
            die_with_parent(&mut command);
            command.spawn().expect("sleep starts").id()
        })
        .join()
        .unwrap();
        // Reap it (it is this process's child) and check it ended by the signal.
        let start = Instant::now();
        let mut status = 0;
        let reaped = unsafe { libc::waitpid(pid as libc::pid_t, &mut status, 0) };
        assert_eq!(reaped, pid as libc::pid_t);
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "{:?}",
            start.elapsed()
        );
        assert!(libc::WIFSIGNALED(status), "status {status}");
        assert_eq!(libc::WTERMSIG(status), libc::SIGTERM);
    }
}
