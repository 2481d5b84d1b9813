//! What may be written where, judged before any work and again under the folder's lock: a
//! folder that is new, empty or this tool's (its manifest), whose entries under the names to be
//! written are the tool's own, with no link out of it.

use super::error::{io, OutputError};
use super::manifest::{Manifest, MANIFEST};
use std::path::Path;

/// Checks, before any work, that `dir` may be written by this tool with the entries `names`:
/// a writable folder (or one that can be made) that is new, empty or this tool's, whose
/// entries under `names` are the tool's, with no link out of it; `force` allows a folder or
/// names that are not the tool's. Reads only.
pub fn check(flag: &str, dir: &Path, names: &[&str], force: bool) -> Result<(), OutputError> {
    crate::atomic::check_writable_dir(flag, dir).map_err(|reason| OutputError::Unusable {
        flag: flag.into(),
        dir: dir.to_path_buf(),
        reason: reason
            .strip_prefix(&format!("{flag} {}: ", dir.display()))
            .unwrap_or(&reason)
            .to_string(),
    })?;
    if !dir.is_dir() || force {
        return Ok(());
    }
    let manifest = Manifest::read(dir);
    judge(flag, dir, manifest.as_ref(), names)
}

/// The refusals of [`check`] for an existing folder, without `--force`.
pub(super) fn judge(
    flag: &str,
    dir: &Path,
    manifest: Option<&Manifest>,
    names: &[&str],
) -> Result<(), OutputError> {
    let entries: Vec<String> = std::fs::read_dir(dir)
        .map_err(io(dir))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != MANIFEST)
        .collect();
    let Some(manifest) = manifest else {
        if entries.is_empty() {
            return Ok(());
        }
        let mut shown: Vec<&String> = entries.iter().collect();
        shown.sort();
        let mut names = shown
            .iter()
            .take(3)
            .map(|n| crate::term::one_line(n).into_owned())
            .collect::<Vec<_>>()
            .join(", ");
        if shown.len() > 3 {
            names += ", …";
        }
        return Err(OutputError::NotOurs {
            flag: flag.into(),
            dir: dir.to_path_buf(),
            count: entries.len(),
            names,
        });
    };
    for name in &entries {
        let path = dir.join(name);
        if let Some(target) = link_out(dir, &path) {
            return Err(OutputError::LinkOut {
                flag: flag.into(),
                dir: dir.to_path_buf(),
                name: name.clone(),
                target,
            });
        }
    }
    for name in names {
        let path = dir.join(name);
        if path.symlink_metadata().is_ok() && !manifest.owns(dir, name) {
            return Err(OutputError::NotOurFile {
                flag: flag.into(),
                path,
            });
        }
    }
    Ok(())
}

/// Where `path` leads when it is a symbolic link to somewhere outside `dir` (or to nothing).
fn link_out(dir: &Path, path: &Path) -> Option<String> {
    let meta = path.symlink_metadata().ok()?;
    if !meta.file_type().is_symlink() {
        return None;
    }
    let target = std::fs::read_link(path).ok()?;
    let shown = target.display().to_string();
    match (std::fs::canonicalize(path), std::fs::canonicalize(dir)) {
        (Ok(t), Ok(d)) if t.starts_with(&d) => None,
        _ => Some(shown),
    }
}

/// Marks `dir` as `program`'s where it holds nothing but `names` (and the lock file versions
/// before the mark used) and `made_here` says the files are the tool's (a run folder of an
/// earlier version, recognised by its report): the files listed as they are. Whether it did.
pub fn adopt(
    dir: &Path,
    program: &str,
    names: &[&str],
    made_here: impl Fn(&Path) -> bool,
) -> Result<bool, OutputError> {
    if Manifest::read(dir).is_some() || !dir.is_dir() {
        return Ok(false);
    }
    let mut manifest = Manifest::new(program);
    let mut lock = None;
    for entry in std::fs::read_dir(dir).map_err(io(dir))? {
        let entry = entry.map_err(io(dir))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let meta = entry.path().symlink_metadata().map_err(io(dir))?;
        if name == ".lock" && meta.is_file() && meta.len() == 0 {
            lock = Some(entry.path());
            continue;
        }
        if !meta.is_file() || !names.contains(&name.as_str()) {
            return Ok(false);
        }
        manifest
            .entries
            .insert(name, super::manifest::Identity::of(&meta));
    }
    if manifest.entries.is_empty() || !made_here(dir) {
        return Ok(false);
    }
    let path = dir.join(MANIFEST);
    crate::atomic::write_whole(&path, &manifest.bytes(program)).map_err(io(&path))?;
    // The empty lock file those versions left: the folder itself is locked now.
    if let Some(lock) = lock {
        let _ = std::fs::remove_file(lock);
    }
    Ok(true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_folder_of_an_earlier_version_is_adopted_and_nothing_else() {
        let tmp = tempfile::tempdir().unwrap();
        let names = ["report.json", "metrics.csv"];
        let ours = |d: &Path| {
            std::fs::read_to_string(d.join("report.json")).is_ok_and(|t| t.contains("estimate"))
        };
        let folder = |name: &str, files: &[(&str, &str)]| {
            let d = tmp.path().join(name);
            std::fs::create_dir(&d).unwrap();
            for (f, text) in files {
                std::fs::write(d.join(f), text).unwrap();
            }
            d
        };
        let old = folder(
            "old",
            &[
                ("report.json", "estimate"),
                ("metrics.csv", "x"),
                (".lock", ""),
            ],
        );
        assert!(adopt(&old, "estimate", &names, ours).unwrap());
        assert!(check("--out", &old, &names, false).is_ok());
        assert!(!old.join(".lock").exists());
        let mixed = folder(
            "mixed",
            &[("report.json", "estimate"), ("notes.txt", "mine")],
        );
        assert!(!adopt(&mixed, "estimate", &names, ours).unwrap());
        let foreign = folder("foreign", &[("report.json", "my own report")]);
        assert!(!adopt(&foreign, "estimate", &names, ours).unwrap());
        assert!(check("--out", &foreign, &names, false).is_err());
    }
}
