//! `OutputDir`: a folder being written by this tool, locked (on the folder itself), marked by
//! its manifest, written one whole file at a time, and removed again if this run created it
//! and wrote nothing of its own into it.

use super::check::{check, judge};
use super::error::{io, OutputError};
use super::manifest::{Identity, Manifest, MANIFEST};
use crate::atomic::PendingFile;
use crate::interrupt::{Kind, Registered};
use std::fs::File;
use std::path::{Path, PathBuf};

/// How long [`OutputDir::open`] waits for another run's lock on the folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wait {
    /// Until it is free: two runs into one folder take turns.
    Turns,
    /// Not at all: the folder is busy (a batch runs for hours).
    Refuse,
}

/// A folder being written by this tool: locked, marked, and written one whole file at a time.
pub struct OutputDir {
    path: PathBuf,
    flag: String,
    program: &'static str,
    manifest: Manifest,
    force: bool,
    _lock: File,
    /// Set while a folder this run created holds nothing of its own yet (and the run is not
    /// over).
    created: Option<Registered>,
}

impl OutputDir {
    /// Opens `dir` (created if missing) for `program` to write `names` into, after the same
    /// checks as [`check`], under an exclusive lock held until dropped (waiting for it as
    /// `wait` says), and marks it as this tool's.
    pub fn open(
        flag: &str,
        dir: &Path,
        program: &'static str,
        names: &[&str],
        force: bool,
        wait: Wait,
    ) -> Result<OutputDir, OutputError> {
        check(flag, dir, names, force)?;
        let created = !dir.exists();
        if created {
            std::fs::create_dir_all(dir).map_err(io(dir))?;
        }
        let registered = created.then(|| Registered::new(Kind::NewFolder(MANIFEST), dir));
        let lock = File::open(dir).map_err(io(dir))?;
        let locked = match wait {
            Wait::Turns => lock.lock().map(|()| true),
            Wait::Refuse => match lock.try_lock() {
                Ok(()) => Ok(true),
                Err(std::fs::TryLockError::WouldBlock) => Ok(false),
                Err(std::fs::TryLockError::Error(e)) => Err(e),
            },
        }
        .map_err(io(dir))?;
        if !locked {
            return Err(OutputError::Busy {
                flag: flag.into(),
                dir: dir.to_path_buf(),
            });
        }
        // Checked again under the lock: another run may have written meanwhile.
        let manifest = Manifest::read(dir);
        if !force {
            judge(flag, dir, manifest.as_ref(), names)?;
        }
        let mut out = OutputDir {
            path: dir.to_path_buf(),
            flag: flag.into(),
            program,
            manifest: manifest.unwrap_or_else(|| Manifest::new(program)),
            force,
            _lock: lock,
            created: registered,
        };
        out.save_manifest()?;
        Ok(out)
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether `name` in the folder is what this tool wrote there.
    pub fn owns(&self, name: &str) -> bool {
        self.manifest.owns(&self.path, name)
    }

    /// Removes those of `names` that this tool wrote here (an earlier run's outputs); any other
    /// file under one of those names stays.
    pub fn remove_own(&mut self, names: &[&str]) -> Result<(), OutputError> {
        for name in names {
            let path = self.path.join(name);
            if self.owns(name) {
                std::fs::remove_file(&path).map_err(io(&path))?;
            }
            self.manifest.entries.remove(*name);
        }
        self.save_manifest()
    }

    /// Removes `name` before it is written anew (a data set's meta.json, so that an interrupted
    /// overwrite is not read as complete): when it is this tool's, or --force allowed
    /// replacing it.
    pub fn remove_to_replace(&mut self, name: &str) -> Result<(), OutputError> {
        self.check_name(name)?;
        let path = self.path.join(name);
        match path.symlink_metadata() {
            Ok(meta) if !meta.is_dir() => {
                std::fs::remove_file(&path).map_err(io(&path))?;
                self.manifest.entries.remove(name);
                self.save_manifest()
            }
            _ => Ok(()),
        }
    }

    /// Writes `bytes` as `name`, whole (a temporary file renamed into place), and records it.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<(), OutputError> {
        use std::io::Write;
        let path = self.path.join(name);
        let mut pending = self.pending(name)?;
        pending.file().write_all(bytes).map_err(io(&path))?;
        self.commit(name, pending)
    }

    /// A file to stream into, to become `name` at [`OutputDir::commit`].
    pub fn pending(&self, name: &str) -> Result<PendingFile, OutputError> {
        let path = self.path.join(name);
        self.check_name(name)?;
        PendingFile::create(&path).map_err(io(&path))
    }

    /// Renames `pending` into place as `name` and records it.
    pub fn commit(&mut self, name: &str, pending: PendingFile) -> Result<(), OutputError> {
        let path = self.path.join(name);
        self.check_name(name)?;
        let meta = pending.commit().map_err(io(&path))?;
        self.manifest
            .entries
            .insert(name.to_string(), Identity::of(&meta));
        self.created = None;
        self.save_manifest()
    }

    /// The folder `name` inside this one (a batch's row), created and recorded, or this tool's
    /// from before; a link there, or a folder the tool did not make, is refused (but with
    /// --force, a plain folder).
    pub fn subfolder(&mut self, name: &str) -> Result<PathBuf, OutputError> {
        let path = self.path.join(name);
        match path.symlink_metadata() {
            Ok(meta) if meta.file_type().is_symlink() => {
                return Err(OutputError::LinkOut {
                    flag: self.flag.clone(),
                    dir: self.path.clone(),
                    name: name.into(),
                    target: std::fs::read_link(&path)
                        .map_or_else(|_| "?".into(), |t| t.display().to_string()),
                });
            }
            Ok(meta) if meta.is_dir() && (self.force || self.owns(name)) => return Ok(path),
            Ok(_) => {
                return Err(OutputError::NotOurFile {
                    flag: self.flag.clone(),
                    path,
                })
            }
            Err(_) => {}
        }
        std::fs::create_dir(&path).map_err(io(&path))?;
        let meta = path.symlink_metadata().map_err(io(&path))?;
        self.manifest
            .entries
            .insert(name.to_string(), Identity::of(&meta));
        self.created = None;
        self.save_manifest()?;
        Ok(path)
    }

    /// A name of one entry inside the folder: no separator, no `..`, not the manifest, and not
    /// another's file (unless --force).
    fn check_name(&self, name: &str) -> Result<(), OutputError> {
        let plain = !name.is_empty()
            && name != "."
            && name != ".."
            && name != MANIFEST
            && !name.contains(['/', '\\']);
        assert!(plain, "an output's name is one plain entry: {name:?}");
        let path = self.path.join(name);
        if !self.force && path.symlink_metadata().is_ok() && !self.owns(name) {
            return Err(OutputError::NotOurFile {
                flag: self.flag.clone(),
                path,
            });
        }
        Ok(())
    }

    fn save_manifest(&mut self) -> Result<(), OutputError> {
        let path = self.path.join(MANIFEST);
        crate::atomic::write_whole(&path, &self.manifest.bytes(self.program)).map_err(io(&path))
    }

    /// The run is over: the folder stays, whatever it holds.
    pub fn finish(mut self) {
        self.created = None;
    }
}

impl Drop for OutputDir {
    /// A folder this run created and wrote nothing of its own into is removed again (a run
    /// refused or failed leaves no empty folder behind).
    fn drop(&mut self) {
        if self.created.is_some() {
            crate::interrupt::remove_if_unfilled(&self.path, MANIFEST);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAMES: [&str; 2] = ["report.json", "metrics.csv"];

    fn open(dir: &Path, force: bool) -> Result<OutputDir, OutputError> {
        OutputDir::open("--out", dir, "estimate", &NAMES, force, Wait::Refuse)
    }

    #[test]
    fn a_folder_of_the_users_is_refused_and_with_force_only_the_written_names_change() {
        let tmp = tempfile::tempdir().unwrap();
        let home = tmp.path();
        std::fs::write(home.join("metrics.csv"), b"mine").unwrap();
        std::fs::write(home.join("notes.txt"), b"mine too").unwrap();
        let e = open(home, false).err().expect("refused");
        assert!(matches!(e, OutputError::NotOurs { count: 2, .. }), "{e}");
        assert!(e.to_string().contains("--force"), "{e}");
        let mut out = open(home, true).unwrap();
        out.remove_own(&NAMES).unwrap();
        out.write("report.json", b"{}").unwrap();
        out.finish();
        assert_eq!(std::fs::read(home.join("metrics.csv")).unwrap(), b"mine");
        assert_eq!(std::fs::read(home.join("notes.txt")).unwrap(), b"mine too");
    }

    #[test]
    fn the_tools_own_folder_is_rewritten_but_a_file_put_under_its_name_is_not() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("run");
        let mut out = open(&dir, false).unwrap();
        out.write("report.json", b"{}").unwrap();
        out.write("metrics.csv", b"a,b").unwrap();
        drop(out);
        let mut again = open(&dir, false).unwrap();
        again.remove_own(&NAMES).unwrap();
        assert!(!dir.join("report.json").exists());
        again.write("report.json", b"{\"x\": 1}").unwrap();
        drop(again);
        // The user puts a file of their own where the tool's was.
        std::fs::write(dir.join("metrics.csv"), b"mine").unwrap();
        let e = open(&dir, false).err().expect("refused");
        assert!(matches!(e, OutputError::NotOurFile { .. }), "{e}");
        // A note of another name in the tool's folder is no reason to refuse.
        std::fs::remove_file(dir.join("metrics.csv")).unwrap();
        std::fs::write(dir.join("notes.txt"), b"mine").unwrap();
        let mut third = open(&dir, false).unwrap();
        third.remove_own(&NAMES).unwrap();
        assert_eq!(std::fs::read(dir.join("notes.txt")).unwrap(), b"mine");
    }

    #[test]
    fn a_folder_made_and_left_unfilled_is_removed_and_a_busy_one_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("new");
        drop(open(&dir, false).unwrap());
        assert!(!dir.exists(), "a refused or failed run leaves no folder");
        let held = open(&dir, false).unwrap();
        let e = open(&dir, false).err().expect("busy");
        assert!(matches!(e, OutputError::Busy { .. }), "{e}");
        drop(held);
        let mut out = open(&dir, false).unwrap();
        out.write("report.json", b"{}").unwrap();
        drop(out);
        assert!(dir.join("report.json").exists(), "a filled folder stays");
    }

    #[cfg(unix)]
    #[test]
    fn links_out_of_the_folder_are_refused_and_never_written_through() {
        let tmp = tempfile::tempdir().unwrap();
        let victim = tmp.path().join("victim");
        std::fs::write(&victim, b"precious").unwrap();
        let dir = tmp.path().join("run");
        let mut out = open(&dir, false).unwrap();
        out.write("report.json", b"{}").unwrap();
        drop(out);
        std::fs::remove_file(dir.join("report.json")).unwrap();
        std::os::unix::fs::symlink(&victim, dir.join("report.json")).unwrap();
        let e = open(&dir, false).err().expect("refused");
        assert!(matches!(e, OutputError::LinkOut { .. }), "{e}");
        let mut forced = open(&dir, true).unwrap();
        forced.write("report.json", b"{}").unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
        std::os::unix::fs::symlink(tmp.path(), dir.join("01-row")).unwrap();
        let e = forced.subfolder("01-row").unwrap_err();
        assert!(matches!(e, OutputError::LinkOut { .. }), "{e}");
        assert!(forced.subfolder("02-row").unwrap().is_dir());
    }
}
