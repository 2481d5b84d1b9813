//! A program stopped by a signal (Ctrl-C, SIGTERM, SIGHUP) leaves nothing half-written: what is
//! in flight registers here (temporary files, a folder this run created and has not filled yet,
//! scratch folders, child processes), and once [`install`]ed a signal removes it all and ends
//! the process at once with 128 + the signal's number. The process ends with `_exit`, so no
//! destructor of libtorch's runs while its threads still work (a plain `exit` from the signal's
//! thread crashed there).

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Duration;

/// What a signal must clean up, by kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A temporary file: removed.
    File,
    /// A folder this run created: removed if nothing is in it but the one file named (its
    /// owner's mark).
    NewFolder(&'static str),
    /// A scratch folder this run made: removed with everything in it.
    Scratch,
}

struct Entry {
    id: u64,
    kind: Kind,
    path: PathBuf,
}

struct Registry {
    next: u64,
    entries: Vec<Entry>,
    children: Vec<u32>,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    next: 0,
    entries: Vec::new(),
    children: Vec::new(),
});

fn registry() -> std::sync::MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(|e| e.into_inner())
}

/// A path registered for cleanup until dropped (or [`Registered::keep`]).
#[derive(Debug)]
pub struct Registered(u64);

impl Registered {
    /// Registers `path` as `kind`.
    pub fn new(kind: Kind, path: &Path) -> Registered {
        let mut r = registry();
        r.next += 1;
        let id = r.next;
        r.entries.push(Entry {
            id,
            kind,
            path: path.to_path_buf(),
        });
        Registered(id)
    }

    /// The path is done with (renamed into place, or removed): a signal leaves it alone.
    pub fn keep(self) {}
}

impl Drop for Registered {
    fn drop(&mut self) {
        registry().entries.retain(|e| e.id != self.0);
    }
}

/// Notes that child process `pid` runs: a signal stops it too, until [`child_ended`].
fn child_started(pid: u32) {
    registry().children.push(pid);
}

/// Notes that child process `pid` ended.
fn child_ended(pid: u32) {
    registry().children.retain(|p| *p != pid);
}

/// Runs `command` (its standard streams as it set them) to its end, a signal stopping it
/// meanwhile, and returns its output.
pub fn run_child(command: &mut std::process::Command) -> std::io::Result<std::process::Output> {
    let child = command.spawn()?;
    let pid = child.id();
    child_started(pid);
    let out = child.wait_with_output();
    child_ended(pid);
    out
}

/// From now on SIGINT, SIGTERM and SIGHUP stop the registered children, remove the registered
/// paths, say so on stderr as `program: ...` and end the process with 128 + the signal.
/// Installing twice does nothing more.
pub fn install(program: &'static str) {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    static INSTALLED: std::sync::Once = std::sync::Once::new();
    INSTALLED.call_once(|| {
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            return;
        };
        std::thread::spawn(move || {
            let Some(signal) = signals.forever().next() else {
                return;
            };
            let removed = clean_up();
            let what = if removed.is_empty() {
                String::new()
            } else {
                format!("; removed {}", removed.join(", "))
            };
            crate::term::eprint_line(&format!("{program}: stopped by signal {signal}{what}"));
            // SAFETY: _exit ends the process without running destructors or atexit handlers,
            // which other threads (libtorch's) may be using.
            unsafe { libc::_exit(128 + signal) }
        });
    });
}

/// Stops the registered children and removes every registered path; what was removed, for
/// the message.
fn clean_up() -> Vec<String> {
    let (children, entries): (Vec<u32>, Vec<(Kind, PathBuf)>) = {
        let r = registry();
        (
            r.children.clone(),
            r.entries.iter().map(|e| (e.kind, e.path.clone())).collect(),
        )
    };
    for pid in children {
        // SAFETY: kill has no memory effects; a child already gone makes it fail harmlessly.
        unsafe {
            libc::kill(pid as libc::pid_t, libc::SIGTERM);
        }
    }
    remove_all(&entries)
}

/// Removes `entries` as their kinds say, files first, then the folders (the latest
/// registered first); what was removed of the folders, for the message.
fn remove_all(entries: &[(Kind, PathBuf)]) -> Vec<String> {
    for (_, path) in entries.iter().filter(|e| e.0 == Kind::File) {
        let _ = std::fs::remove_file(path);
    }
    let mut removed = Vec::new();
    for (kind, path) in entries.iter().rev() {
        let (gone, what) = match kind {
            Kind::File => continue,
            Kind::Scratch => (remove_tree(path), "the scratch directory"),
            Kind::NewFolder(mark) => (remove_if_unfilled(path, mark), "the unfilled folder"),
        };
        if gone {
            removed.push(format!("{what} {}", path.display()));
        }
    }
    removed
}

/// Removes `dir` if it holds nothing but, perhaps, the file `mark`; whether it did.
pub fn remove_if_unfilled(dir: &Path, mark: &str) -> bool {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return false;
    };
    let names: Vec<_> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name())
        .collect();
    if names.iter().any(|n| n != mark) {
        return false;
    }
    let _ = std::fs::remove_file(dir.join(mark));
    std::fs::remove_dir(dir).is_ok()
}

/// Removes `dir` and everything in it, trying again for a second while a child may still add
/// files; whether it is gone.
fn remove_tree(dir: &Path) -> bool {
    for _ in 0..20 {
        match std::fs::remove_dir_all(dir) {
            Ok(()) => return true,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return false,
            Err(_) => std::thread::sleep(Duration::from_millis(50)),
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_registration_lasts_as_long_as_its_guard() {
        let path = Path::new("/nonexistent/registered-by-a-test");
        let listed = || registry().entries.iter().any(|e| e.path == path);
        let guard = Registered::new(Kind::File, path);
        assert!(listed());
        guard.keep();
        assert!(!listed());
    }

    #[test]
    fn cleanup_removes_temporary_files_and_unfilled_new_folders_only() {
        let dir = tempfile::tempdir().unwrap();
        let left = dir.path().join("left.partial");
        std::fs::write(&left, b"x").unwrap();
        let new = dir.path().join("new");
        std::fs::create_dir(&new).unwrap();
        std::fs::write(new.join(".mark"), b"{}").unwrap();
        let filled = dir.path().join("filled");
        std::fs::create_dir(&filled).unwrap();
        std::fs::write(filled.join("report.json"), b"{}").unwrap();
        let scratch = dir.path().join("scratch");
        std::fs::create_dir_all(scratch.join("a/b")).unwrap();
        let removed = remove_all(&[
            (Kind::NewFolder(".mark"), new.clone()),
            (Kind::File, left.clone()),
            (Kind::NewFolder(".mark"), filled.clone()),
            (Kind::Scratch, scratch.clone()),
        ]);
        assert!(!left.exists());
        assert!(!new.exists(), "a new folder with only its mark goes");
        assert!(filled.join("report.json").exists(), "a filled folder stays");
        assert!(!scratch.exists());
        assert_eq!(removed.len(), 2, "{removed:?}");
    }
}
