//! Writing a dataset: `DatasetWriter` streams `frames.npy` under a temporary name and renames
//! everything into place at the end, `meta.json` last, so an interrupted write never leaves a
//! directory that looks like a complete dataset.

use super::{FRAMES_FILE, META_FILE, PREVIEW_FILE};
use crate::atomic::partial_path as partial;
use crate::error::DatasetError;
use crate::meta::DatasetMeta;
use crate::npy::{header_bytes, write_f32_le};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Paths of a written dataset.
#[derive(Debug, Clone)]
pub struct DatasetFiles {
    pub frames: PathBuf,
    pub meta: PathBuf,
    pub preview: PathBuf,
}

/// Refuses an existing non-empty directory unless `force`; a path that exists but is not a
/// directory is always refused.
pub fn check_output_dir(dir: &Path, force: bool) -> Result<(), DatasetError> {
    match std::fs::read_dir(dir) {
        Ok(mut entries) => {
            if entries.next().is_some() && !force {
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

fn write_partial(path: &Path, bytes: &[u8]) -> Result<PathBuf, DatasetError> {
    let tmp = partial(path);
    let err = write_err(&tmp);
    let file = File::create(&tmp).map_err(&err)?;
    (&file).write_all(bytes).map_err(&err)?;
    file.sync_all().map_err(&err)?;
    Ok(tmp)
}

/// Streams a dataset to disk: `frames.npy` is written under a temporary name as frames arrive
/// (each piece flushed to the device as it goes, so the final sync is short), and
/// [`DatasetWriter::finish`] renames everything into place, `meta.json` last. Any stale
/// `meta.json` is removed first, so a crash part-way through an overwrite leaves a directory
/// without `meta.json`, which the reader refuses; dropping an unfinished writer removes its
/// temporary files.
pub struct DatasetWriter {
    files: DatasetFiles,
    frames_tmp: PathBuf,
    out: BufWriter<File>,
    expected: usize,
    written: usize,
    finished: bool,
}

impl DatasetWriter {
    /// Prepares `dir` (refusing a non-empty one unless `force`) and writes the `.npy` header.
    pub fn create(
        dir: &Path,
        shape: [usize; 5],
        force: bool,
    ) -> Result<DatasetWriter, DatasetError> {
        check_output_dir(dir, force)?;
        std::fs::create_dir_all(dir).map_err(write_err(dir))?;
        let files = DatasetFiles {
            frames: dir.join(FRAMES_FILE),
            meta: dir.join(META_FILE),
            preview: dir.join(PREVIEW_FILE),
        };
        match std::fs::remove_file(&files.meta) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(write_err(&files.meta)(e))
            }
            _ => {}
        }
        let frames_tmp = partial(&files.frames);
        let file = File::create(&frames_tmp).map_err(write_err(&frames_tmp))?;
        let mut writer = DatasetWriter {
            files,
            out: BufWriter::with_capacity(1 << 20, file),
            expected: shape.iter().product(),
            written: 0,
            finished: false,
            frames_tmp,
        };
        let header = header_bytes(&shape);
        writer
            .out
            .write_all(&header)
            .map_err(write_err(&writer.frames_tmp))?;
        Ok(writer)
    }

    /// Appends frames (C order) and flushes them to the device.
    pub fn write_frames(&mut self, frames: &[f32]) -> Result<(), DatasetError> {
        assert!(
            self.written + frames.len() <= self.expected,
            "more frames than the shape holds"
        );
        let err = write_err(&self.frames_tmp);
        write_f32_le(&mut self.out, frames).map_err(&err)?;
        self.out.flush().map_err(&err)?;
        self.out.get_ref().sync_data().map_err(&err)?;
        self.written += frames.len();
        Ok(())
    }

    /// Writes the preview and the metadata and renames all three files into place.
    pub fn finish(
        mut self,
        meta: &DatasetMeta,
        preview_png: &[u8],
    ) -> Result<DatasetFiles, DatasetError> {
        assert_eq!(self.written, self.expected, "frames.npy is incomplete");
        let err = write_err(&self.frames_tmp);
        self.out.flush().map_err(&err)?;
        self.out.get_ref().sync_all().map_err(&err)?;
        let preview_tmp = write_partial(&self.files.preview, preview_png)?;
        let meta_json = serde_json::to_vec_pretty(meta).expect("metadata serialises");
        let meta_tmp = write_partial(&self.files.meta, &meta_json)?;
        for (tmp, fin) in [
            (&self.frames_tmp, &self.files.frames),
            (&preview_tmp, &self.files.preview),
            (&meta_tmp, &self.files.meta),
        ] {
            std::fs::rename(tmp, fin).map_err(write_err(fin))?;
        }
        if let Some(dir) = self.files.meta.parent() {
            if let Ok(d) = File::open(dir) {
                let _ = d.sync_all();
            }
        }
        self.finished = true;
        Ok(self.files.clone())
    }
}

impl Drop for DatasetWriter {
    fn drop(&mut self) {
        if !self.finished {
            for f in [&self.files.frames, &self.files.preview, &self.files.meta] {
                let _ = std::fs::remove_file(partial(f));
            }
        }
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
