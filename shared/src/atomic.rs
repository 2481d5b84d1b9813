//! Writing files so that a reader never sees half of one and a planted link is never followed:
//! a file is written under a fresh random name beside its target (created exclusively, so no
//! existing file or link is opened), then renamed over the target (a rename replaces a link at
//! the target's name; it does not write through it). A signal or an error removes the
//! temporary file (`interrupt`).

use crate::error::DatasetError;
use crate::interrupt::{Kind, Registered};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Suffix of files being written.
pub const PARTIAL_SUFFIX: &str = ".partial";

/// A file being written beside `target` under a temporary name: [`PendingFile::commit`] renames
/// it into place; dropped uncommitted, it is removed.
pub struct PendingFile {
    file: tempfile::NamedTempFile,
    target: PathBuf,
    _registered: Registered,
}

impl PendingFile {
    /// Creates the temporary file `.NAME.RANDOM.partial` in `target`'s folder, readable as a
    /// plain file would be (0666 less the umask).
    pub fn create(target: &Path) -> std::io::Result<PendingFile> {
        let dir = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let name = target
            .file_name()
            .map_or_else(|| "file".into(), |n| n.to_string_lossy());
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(PARTIAL_SUFFIX).rand_bytes(8);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        let file = builder.tempfile_in(dir)?;
        let registered = Registered::new(Kind::File, file.path());
        Ok(PendingFile {
            file,
            target: target.to_path_buf(),
            _registered: registered,
        })
    }

    /// The file to write.
    pub fn file(&mut self) -> &mut std::fs::File {
        self.file.as_file_mut()
    }

    /// The temporary file's path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Renames the file into place; the file's metadata after the rename (its identity for an
    /// outputs manifest). (A caller that needs the data on the device first syncs the file.)
    pub fn commit(mut self) -> std::io::Result<std::fs::Metadata> {
        self.file.as_file_mut().flush()?;
        let meta = self.file.as_file().metadata()?;
        self.file
            .persist(&self.target)
            .map_err(|e| e.error)
            .map(|_| meta)
    }
}

impl Write for PendingFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.as_file_mut().write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.as_file_mut().flush()
    }
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), DatasetError> {
    write_whole(path, bytes).map_err(|source| DatasetError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// [`write_atomic`] with the I/O error as it is.
pub fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut pending = PendingFile::create(path)?;
    pending.file().write_all(bytes)?;
    pending.commit().map(|_| ())
}

/// Checks, before any work, that `dir` is or can become a writable directory: it is one, or
/// does not exist and its nearest existing ancestor is one. Names the path and the fault.
pub fn check_writable_dir(flag: &str, dir: &Path) -> Result<(), String> {
    let shown = dir.display();
    if dir.symlink_metadata().is_ok() && dir.metadata().is_err() {
        return Err(format!(
            "{flag} {shown}: a symbolic link to nothing; remove it or choose another directory"
        ));
    }
    let existing = dir
        .ancestors()
        .find(|p| p.exists())
        .unwrap_or(Path::new("."));
    let existing = if existing.as_os_str().is_empty() {
        Path::new(".")
    } else {
        existing
    };
    if !existing.is_dir() {
        return Err(if existing == dir {
            format!("{flag} {shown}: is a file or device, not a directory; choose a directory (created if missing)")
        } else {
            format!(
                "{flag} {shown}: {} is a file, not a directory; choose another path",
                existing.display()
            )
        });
    }
    // Writable: a probe file created exclusively under a random name and removed
    // (permissions alone miss read-only mounts).
    match tempfile::Builder::new()
        .prefix(".physvid-probe-")
        .tempfile_in(existing)
    {
        Ok(_) => Ok(()),
        Err(e) => Err(format!(
            "{flag} {shown}: cannot write in {} ({e}); choose a writable directory",
            existing.display()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(PARTIAL_SUFFIX))
            .collect()
    }

    #[test]
    fn a_file_appears_whole_and_no_temporary_file_stays() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.json");
        write_atomic(&p, b"{}").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"{}");
        assert!(leftovers(dir.path()).is_empty());
        let pending = PendingFile::create(&dir.path().join("y.csv")).unwrap();
        assert_eq!(leftovers(dir.path()).len(), 1);
        drop(pending);
        assert!(
            leftovers(dir.path()).is_empty(),
            "dropped uncommitted: removed"
        );
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&p).unwrap().permissions().mode();
            assert_ne!(
                mode & 0o044,
                0,
                "readable by others as a plain file: {mode:o}"
            );
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_link_planted_at_the_target_or_a_temporary_name_is_never_written_through() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        std::fs::write(&victim, b"precious").unwrap();
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        // The old fixed temporary name and the target itself, both links to the victim.
        std::os::unix::fs::symlink(&victim, out.join("table.md.partial")).unwrap();
        std::os::unix::fs::symlink(&victim, out.join("table.md")).unwrap();
        write_atomic(&out.join("table.md"), b"new").unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
        assert_eq!(std::fs::read(out.join("table.md")).unwrap(), b"new");
        assert!(!out
            .join("table.md")
            .symlink_metadata()
            .unwrap()
            .is_symlink());
    }

    #[test]
    fn output_directories_are_checked_before_work() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("f");
        std::fs::write(&file, b"x").unwrap();
        assert!(check_writable_dir("--out", &tmp.path().join("new/run")).is_ok());
        assert!(check_writable_dir("--out", tmp.path()).is_ok());
        let e = check_writable_dir("--out", &file).unwrap_err();
        assert!(e.contains("not a directory"), "{e}");
        let e = check_writable_dir("--out", &file.join("run")).unwrap_err();
        assert!(e.contains("is a file"), "{e}");
        #[cfg(unix)]
        {
            let link = tmp.path().join("dangling");
            std::os::unix::fs::symlink(tmp.path().join("nowhere"), &link).unwrap();
            let e = check_writable_dir("--out", &link).unwrap_err();
            assert!(e.contains("symbolic link"), "{e}");
            let e = check_writable_dir("--out", Path::new("/proc/x")).unwrap_err();
            assert!(e.contains("cannot write"), "{e}");
        }
    }
}
