//! The mark of a folder this tool owns: `.physvid-outputs.json`, the files (and a batch's row
//! folders) it wrote there, each with its identity when written (device, inode, size and
//! modification time), so that a file the user later replaced or edited under the same name
//! is told apart from the tool's own.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The manifest's file name.
pub const MANIFEST: &str = ".physvid-outputs.json";

/// The manifest's `format`.
const FORMAT: &str = "physvid-outputs";

/// What the manifest holds.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Manifest {
    pub format: String,
    pub version: u32,
    /// The program and version that last wrote into the folder.
    pub written_by: String,
    /// What this tool wrote, by name within the folder.
    pub entries: BTreeMap<String, Identity>,
}

/// A written file's or folder's identity: it is still the tool's while these agree.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
pub struct Identity {
    pub device: u64,
    pub inode: u64,
    /// Bytes, for a file.
    pub bytes: Option<u64>,
    /// Nanoseconds since the epoch of the last change, for a file.
    pub modified_ns: Option<i128>,
}

impl Identity {
    /// The identity of what `meta` describes (a folder's size and time change with its
    /// contents, so a folder is known by device and inode alone).
    pub fn of(meta: &std::fs::Metadata) -> Identity {
        #[cfg(unix)]
        let (device, inode) = {
            use std::os::unix::fs::MetadataExt;
            (meta.dev(), meta.ino())
        };
        #[cfg(not(unix))]
        let (device, inode) = (0, 0);
        let file = meta.is_file();
        Identity {
            device,
            inode,
            bytes: file.then_some(meta.len()),
            modified_ns: meta
                .modified()
                .ok()
                .filter(|_| file)
                .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
                .map(|d| d.as_nanos() as i128),
        }
    }
}

impl Manifest {
    /// An empty manifest for `program`.
    pub fn new(program: &str) -> Manifest {
        Manifest {
            format: FORMAT.into(),
            version: 1,
            written_by: written_by(program),
            entries: BTreeMap::new(),
        }
    }

    /// The manifest of `dir`, if it has a readable one that is a plain file (a link or a
    /// malformed file is no mark).
    pub fn read(dir: &Path) -> Option<Manifest> {
        let path = dir.join(MANIFEST);
        let meta = path.symlink_metadata().ok()?;
        if !meta.is_file() || meta.len() > 16 << 20 {
            return None;
        }
        let m: Manifest = serde_json::from_slice(&std::fs::read(&path).ok()?).ok()?;
        (m.format == FORMAT).then_some(m)
    }

    /// Whether `name` in `dir` is what this tool wrote there (not a link; the same identity).
    pub fn owns(&self, dir: &Path, name: &str) -> bool {
        let Some(mark) = self.entries.get(name) else {
            return false;
        };
        match dir.join(name).symlink_metadata() {
            Ok(meta) if !meta.file_type().is_symlink() => Identity::of(&meta) == *mark,
            _ => false,
        }
    }

    /// The manifest's bytes, with `program` as the last writer.
    pub fn bytes(&mut self, program: &str) -> Vec<u8> {
        self.written_by = written_by(program);
        serde_json::to_vec_pretty(self).expect("a manifest serialises")
    }
}

fn written_by(program: &str) -> String {
    format!("{program} {}", env!("CARGO_PKG_VERSION"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_owned_while_its_identity_holds() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("report.json");
        std::fs::write(&p, b"{}").unwrap();
        let mut m = Manifest::new("estimate");
        m.entries
            .insert("report.json".into(), Identity::of(&p.metadata().unwrap()));
        assert!(m.owns(dir.path(), "report.json"));
        assert!(!m.owns(dir.path(), "metrics.csv"));
        // Replaced by the user under the same name: another inode.
        std::fs::remove_file(&p).unwrap();
        std::fs::write(&p, b"{}").unwrap();
        let same_inode =
            m.entries["report.json"].inode == Identity::of(&p.metadata().unwrap()).inode;
        if !same_inode {
            assert!(!m.owns(dir.path(), "report.json"));
        }
        // Edited in place: its size changes.
        m.entries
            .insert("report.json".into(), Identity::of(&p.metadata().unwrap()));
        std::fs::write(&p, b"{\"mine\": 1}").unwrap();
        assert!(!m.owns(dir.path(), "report.json"));
        std::fs::write(dir.path().join(MANIFEST), m.bytes("estimate")).unwrap();
        assert_eq!(Manifest::read(dir.path()), Some(m));
        std::fs::write(dir.path().join(MANIFEST), b"not json").unwrap();
        assert_eq!(Manifest::read(dir.path()), None);
    }
}
