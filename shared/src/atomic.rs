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
}
