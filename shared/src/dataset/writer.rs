//! Writing a dataset: `DatasetWriter` streams `frames.npy` under a temporary name into a folder
//! this tool owns (`outdir`) and renames everything into place at the end, `meta.json` last, so
//! an interrupted write never leaves a directory that looks like a complete dataset.

use super::{FRAMES_FILE, META_FILE, PREVIEW_FILE};
use crate::atomic::PendingFile;
use crate::error::DatasetError;
use crate::meta::DatasetMeta;
use crate::npy::{header_bytes, write_f32_le};
use crate::outdir::{OutputDir, OutputError, Wait, MANIFEST};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Paths of a written dataset.
#[derive(Debug, Clone)]
pub struct DatasetFiles {
    pub frames: PathBuf,
    pub meta: PathBuf,
    pub preview: PathBuf,
}

/// The files a data set is made of.
pub const DATASET_FILES: [&str; 3] = [FRAMES_FILE, META_FILE, PREVIEW_FILE];

/// Refuses an existing folder that holds anything (this tool's own data set too: one takes
/// time to make) unless `force`; a path that exists but is not a directory is always refused.
pub fn check_output_dir(dir: &Path, force: bool) -> Result<(), DatasetError> {
    match std::fs::read_dir(dir) {
        Ok(entries) => {
            let filled = entries
                .filter_map(|e| e.ok())
                .any(|e| e.file_name() != MANIFEST);
            if filled && !force {
                return Err(DatasetError::NotEmpty {
                    path: dir.to_path_buf(),
                });
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(DatasetError::Write {
            path: dir.to_path_buf(),
            source: e,
        }),
    }
}

fn write_err(path: &Path) -> impl Fn(std::io::Error) -> DatasetError {
    let path = path.to_path_buf();
    move |source| DatasetError::Write {
        path: path.clone(),
        source,
    }
}

impl From<OutputError> for DatasetError {
    fn from(e: OutputError) -> DatasetError {
        match e {
            OutputError::Io { path, source } => DatasetError::Write { path, source },
            refusal => DatasetError::Refused(refusal.to_string()),
        }
    }
}

/// Streams a dataset to disk: `frames.npy` is written under a temporary name as frames arrive
/// (each piece flushed to the device as it goes, so the final sync is short), and
/// [`DatasetWriter::finish`] renames everything into place, `meta.json` last. A stale
/// `meta.json` is removed first, so a crash part-way through an overwrite leaves a directory
/// without `meta.json`, which the reader refuses; dropping an unfinished writer removes its
/// temporary files, and the folder if it made it.
pub struct DatasetWriter {
    // Dropped before the folder (fields drop in order): an unfinished write's temporary file
    // goes first, so that a folder this run made is found empty and removed.
    frames: BufWriter<PendingFile>,
    dir: OutputDir,
    expected: usize,
    written: usize,
}

impl DatasetWriter {
    /// Prepares `dir` (refusing a non-empty one unless `force`) and writes the `.npy` header.
    pub fn create(
        dir: &Path,
        shape: [usize; 5],
        force: bool,
    ) -> Result<DatasetWriter, DatasetError> {
        check_output_dir(dir, force)?;
        let mut out = OutputDir::open("--out", dir, "gen", &DATASET_FILES, force, Wait::Refuse)?;
        out.remove_to_replace(META_FILE)?;
        let pending = out.pending(FRAMES_FILE)?;
        let tmp = pending.path().to_path_buf();
        let mut writer = DatasetWriter {
            frames: BufWriter::with_capacity(1 << 20, pending),
            dir: out,
            expected: shape.iter().product(),
            written: 0,
        };
        writer
            .frames
            .write_all(&header_bytes(&shape))
            .map_err(write_err(&tmp))?;
        Ok(writer)
    }

    /// Appends frames (C order) and flushes them to the device.
    pub fn write_frames(&mut self, frames: &[f32]) -> Result<(), DatasetError> {
        assert!(
            self.written + frames.len() <= self.expected,
            "more frames than the shape holds"
        );
        let err = write_err(self.frames.get_ref().path());
        write_f32_le(&mut self.frames, frames).map_err(&err)?;
        self.frames.flush().map_err(&err)?;
        self.frames.get_mut().file().sync_data().map_err(&err)?;
        self.written += frames.len();
        Ok(())
    }

    /// Writes the preview and the metadata and renames all three files into place.
    pub fn finish(
        self,
        meta: &DatasetMeta,
        preview_png: &[u8],
    ) -> Result<DatasetFiles, DatasetError> {
        assert_eq!(self.written, self.expected, "frames.npy is incomplete");
        let DatasetWriter {
            mut dir, frames, ..
        } = self;
        let mut frames = frames
            .into_inner()
            .map_err(|e| write_err(&dir.path().join(FRAMES_FILE))(e.into_error()))?;
        frames
            .file()
            .sync_all()
            .map_err(write_err(&dir.path().join(FRAMES_FILE)))?;
        dir.commit(FRAMES_FILE, frames)?;
        dir.write(PREVIEW_FILE, preview_png)?;
        let meta_json = serde_json::to_vec_pretty(meta).expect("metadata serialises");
        dir.write(META_FILE, &meta_json)?;
        if let Ok(d) = std::fs::File::open(dir.path()) {
            let _ = d.sync_all();
        }
        let files = DatasetFiles {
            frames: dir.path().join(FRAMES_FILE),
            meta: dir.path().join(META_FILE),
            preview: dir.path().join(PREVIEW_FILE),
        };
        dir.finish();
        Ok(files)
    }
}

/// Writes a whole dataset held in memory (see [`DatasetWriter`]).
pub fn write_dataset(
    dir: &Path,
    frames: &[f32],
    meta: &DatasetMeta,
    preview_png: &[u8],
    force: bool,
) -> Result<DatasetFiles, DatasetError> {
    let mut w = DatasetWriter::create(dir, meta.shape, force)?;
    w.write_frames(frames)?;
    w.finish(meta, preview_png)
}
