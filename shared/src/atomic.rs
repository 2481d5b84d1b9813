//! Writing files so that a reader never sees half of one: `write_atomic` writes `NAME.partial`
//! beside the target and renames it into place.

use crate::error::DatasetError;
use std::path::{Path, PathBuf};

/// Suffix of files being written.
pub const PARTIAL_SUFFIX: &str = ".partial";

/// `path` with [`PARTIAL_SUFFIX`] appended to its whole name (`table.md` → `table.md.partial`,
/// so files that differ only in extension never share a temporary name).
pub fn partial_path(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(PARTIAL_SUFFIX);
    PathBuf::from(s)
}

/// Writes `bytes` to `path` through a temporary file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), DatasetError> {
    let tmp = partial_path(path);
    let err = |source| DatasetError::Write {
        path: path.to_path_buf(),
        source,
    };
    std::fs::write(&tmp, bytes).map_err(err)?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        err(e)
    })
}

/// Checks, before any work, that `dir` is or can become a writable directory: it is one, or
/// does not exist and its nearest existing ancestor is one. Names the path and the fault.
pub fn check_output_dir(flag: &str, dir: &Path) -> Result<(), String> {
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
    // Writable: a probe file created and removed (permissions alone miss read-only mounts).
    let probe = existing.join(format!(".physvid-probe-{}", std::process::id()));
    match std::fs::File::create(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(format!(
            "{flag} {shown}: cannot write in {} ({e}); choose a writable directory",
            existing.display()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn siblings_with_other_extensions_get_distinct_temporary_names() {
        let a = partial_path(Path::new("out/table6.md"));
        let b = partial_path(Path::new("out/table6.csv"));
        assert_ne!(a, b);
        assert_eq!(a, Path::new("out/table6.md.partial"));
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.json");
        write_atomic(&p, b"{}").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"{}");
        assert!(!partial_path(&p).exists());
    }

    #[test]
    fn output_directories_are_checked_before_work() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("f");
        std::fs::write(&file, b"x").unwrap();
        assert!(check_output_dir("--out", &tmp.path().join("new/run")).is_ok());
        assert!(check_output_dir("--out", tmp.path()).is_ok());
        let e = check_output_dir("--out", &file).unwrap_err();
        assert!(e.contains("not a directory"), "{e}");
        let e = check_output_dir("--out", &file.join("run")).unwrap_err();
        assert!(e.contains("is a file"), "{e}");
        #[cfg(unix)]
        {
            let link = tmp.path().join("dangling");
            std::os::unix::fs::symlink(tmp.path().join("nowhere"), &link).unwrap();
            let e = check_output_dir("--out", &link).unwrap_err();
            assert!(e.contains("symbolic link"), "{e}");
            let e = check_output_dir("--out", Path::new("/proc/x")).unwrap_err();
            assert!(e.contains("cannot write"), "{e}");
        }
    }
}
