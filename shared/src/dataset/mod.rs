//! The dataset on disk: `frames.npy` ([N, T, C, H, W] float32), `meta.json`, `preview.png`.
//! Written under temporary names and renamed at the end, `meta.json` last, so an interrupted
//! write never leaves a dataset that looks complete; read back with full validation.

mod writer;

use crate::error::DatasetError;
use crate::meta::{DatasetMeta, FORMAT_NAME, FORMAT_VERSION};
use crate::npy::{read_npy, read_npy_shape, NpyArray};
use std::path::{Path, PathBuf};

pub use writer::{check_output_dir, write_dataset, DatasetFiles, DatasetWriter, DATASET_FILES};

pub const FRAMES_FILE: &str = "frames.npy";
pub const META_FILE: &str = "meta.json";
pub const PREVIEW_FILE: &str = "preview.png";

/// A dataset in memory: the frames and, when it came with one, its metadata.
#[derive(Debug, Clone)]
pub struct Dataset {
    /// [N, T, C, H, W].
    pub shape: [usize; 5],
    pub frames: Vec<f32>,
    pub meta: Option<DatasetMeta>,
    pub frames_path: PathBuf,
}

fn bad_meta(path: &Path, reason: impl Into<String>) -> DatasetError {
    DatasetError::BadMeta {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// Checks a parsed `meta.json` against itself and against the frames' shape.
pub fn validate_meta(
    meta: &DatasetMeta,
    meta_path: &Path,
    frames_path: &Path,
    frames_shape: [usize; 5],
) -> Result<(), DatasetError> {
    if meta.format != FORMAT_NAME {
        return Err(bad_meta(
            meta_path,
            format!("format is '{}', expected '{FORMAT_NAME}'", meta.format),
        ));
    }
    if meta.format_version > FORMAT_VERSION {
        return Err(bad_meta(
            meta_path,
            format!(
                "format_version {} is newer than this program reads ({FORMAT_VERSION}); upgrade",
                meta.format_version
            ),
        ));
    }
    if !(meta.dt.is_finite() && meta.dt > 0.0) {
        return Err(bad_meta(
            meta_path,
            format!("dt is {}, must be > 0", meta.dt),
        ));
    }
    let inconsistent = |reason: String| DatasetError::Inconsistent {
        path: meta_path.to_path_buf(),
        other: frames_path.to_path_buf(),
        reason,
    };
    if meta.shape != frames_shape {
        return Err(inconsistent(format!(
            "meta.json says shape {:?}, frames.npy has {:?}",
            meta.shape, frames_shape
        )));
    }
    let [n, t, ..] = frames_shape;
    if meta.samples.len() != n || meta.latents.len() != n {
        return Err(inconsistent(format!(
            "{} samples and {} latent series for N = {n} clips",
            meta.samples.len(),
            meta.latents.len()
        )));
    }
    let dims = meta.latent_dims;
    if dims == 0 {
        return Err(bad_meta(meta_path, "latent_dims is 0, must be at least 1"));
    }
    if let Some((i, l)) = meta
        .latents
        .iter()
        .enumerate()
        .find(|(_, l)| l.len() != t * dims)
    {
        return Err(inconsistent(format!(
            "latent series {i} has {} values for T = {t} frames of {dims} each",
            l.len()
        )));
    }
    if let Some(times) = &meta.clip_start_times {
        if times.len() != n {
            return Err(inconsistent(format!(
                "{} clip_start_times for N = {n} clips",
                times.len()
            )));
        }
        if let Some((i, v)) = times
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v >= 0.0 && **v <= MAX_START_TIME))
        {
            return Err(bad_meta(
                meta_path,
                format!(
                    "clip_start_times[{i}] is {v}, must be a time from 0 to {MAX_START_TIME:e} s"
                ),
            ));
        }
    }
    meta.calibration
        .check()
        .map_err(|e| bad_meta(meta_path, e))?;
    Ok(())
}

/// The latest clip start time taken (s; a year): later ones cannot be a recording's.
pub const MAX_START_TIME: f64 = 3.2e7;

/// Reads and parses a `meta.json` (a FIFO or device refused before it is opened), without
/// checking it against its frames (`read_dataset` does).
pub fn read_meta(path: &Path) -> Result<DatasetMeta, DatasetError> {
    crate::input::check_kind(path).map_err(|e| bad_meta(path, e))?;
    let bytes = std::fs::read(path).map_err(|source| DatasetError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_slice(&bytes)
        .map_err(|e| bad_meta(path, format!("not valid metadata JSON: {e}")))
}

/// A dataset's shape and metadata, validated as `read_dataset` validates them, without its
/// frames (what `estimate` settles its configuration by before loading).
#[derive(Debug, Clone, PartialEq)]
pub struct DatasetHeader {
    /// [N, T, C, H, W].
    pub shape: [usize; 5],
    pub meta: Option<DatasetMeta>,
    pub frames_path: PathBuf,
}

/// Reads `DIR`'s (frames.npy + meta.json) or a bare `.npy` file's header and metadata,
/// validating the rank, the data's length and the metadata's consistency with the shape.
pub fn read_dataset_header(path: &Path) -> Result<DatasetHeader, DatasetError> {
    let (frames_path, meta_path) = if path.is_dir() {
        (path.join(FRAMES_FILE), Some(path.join(META_FILE)))
    } else {
        (path.to_path_buf(), None)
    };
    if let Some(mp) = &meta_path {
        if !mp.exists() {
            return Err(bad_meta(
                mp,
                "missing: the directory is not a complete dataset (an interrupted write?); \
                 pass the .npy file itself to read frames without metadata",
            ));
        }
    }
    let shape = read_npy_shape(&frames_path)?;
    let shape: [usize; 5] = shape
        .clone()
        .try_into()
        .map_err(|_| DatasetError::WrongRank {
            path: frames_path.clone(),
            rank: shape.len(),
            found: shape,
            expected: 5,
            layout: "[N, T, C, H, W]; add axes with arr[:, :, None] for one channel",
        })?;
    let meta = match meta_path {
        None => None,
        Some(mp) => {
            let meta = read_meta(&mp)?;
            validate_meta(&meta, &mp, &frames_path, shape)?;
            Some(meta)
        }
    };
    Ok(DatasetHeader {
        shape,
        meta,
        frames_path,
    })
}

/// Reads `DIR` (frames.npy + meta.json) or a bare `.npy` file (no metadata), validating the
/// header and metadata (`read_dataset_header`) and the values (`DatasetHeader::read_frames`).
pub fn read_dataset(path: &Path) -> Result<Dataset, DatasetError> {
    read_dataset_header(path)?.read_frames()
}

impl DatasetHeader {
    /// The frames this header describes, each value checked finite.
    pub fn read_frames(&self) -> Result<Dataset, DatasetError> {
        let NpyArray { data, .. } = read_npy(&self.frames_path)?;
        if let Some(i) = data.iter().position(|v| !v.is_finite()) {
            let [_, t, c, h, w] = self.shape;
            let per_clip = t * c * h * w;
            return Err(DatasetError::MalformedNpy {
                path: self.frames_path.clone(),
                reason: format!(
                    "value {} at clip {}, frame {} is not finite; frames must hold finite numbers",
                    data[i],
                    i / per_clip,
                    (i % per_clip) / (c * h * w)
                ),
            });
        }
        Ok(Dataset {
            shape: self.shape,
            frames: data,
            meta: self.meta.clone(),
            frames_path: self.frames_path.clone(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::meta::{GeneratorInfo, ModelSpec, SampleTruth};
    use crate::npy::write_npy;

    fn meta(shape: [usize; 5]) -> DatasetMeta {
        DatasetMeta {
            format: FORMAT_NAME.into(),
            format_version: FORMAT_VERSION,
            generator: GeneratorInfo {
                name: "test".into(),
                version: "0".into(),
            },
            scenario: "intensity".into(),
            model: ModelSpec {
                name: "damped-oscillator".into(),
                parameters: Default::default(),
                file: None,
            },
            dt: 0.2,
            shape,
            seed: 0,
            noise: 0.0,
            latent_mapping: String::new(),
            calibration: Default::default(),
            fps: None,
            clip_start_times: None,
            sampling: String::new(),
            samples: vec![SampleTruth::from_pairs([("amplitude", 1.0), ("phase", 0.0)]); shape[0]],
            latent_dims: 1,
            latents: vec![vec![0.0; shape[1]]; shape[0]],
            perturbations: Vec::new(),
        }
    }

    #[test]
    fn write_then_read_round_trips_and_refuses_overwrite() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("ds");
        let shape = [2, 3, 1, 4, 4];
        let frames: Vec<f32> = (0..96).map(|i| i as f32 / 96.0).collect();
        write_dataset(&out, &frames, &meta(shape), b"png", false).unwrap();
        let ds = read_dataset(&out).unwrap();
        assert_eq!(ds.shape, shape);
        assert_eq!(ds.frames, frames);
        assert_eq!(ds.meta.unwrap(), meta(shape));
        let e = write_dataset(&out, &frames, &meta(shape), b"png", false).unwrap_err();
        assert!(e.to_string().contains("--force"));
        write_dataset(&out, &frames, &meta(shape), b"png", true).unwrap();
        let mut names: Vec<_> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                crate::outdir::MANIFEST,
                FRAMES_FILE,
                META_FILE,
                PREVIEW_FILE
            ],
            "no partial files left"
        );
    }

    #[test]
    fn inconsistent_meta_and_missing_meta_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("ds");
        let frames = vec![0.5f32; 96];
        let mut m = meta([2, 3, 1, 4, 4]);
        write_dataset(&out, &frames, &m, b"", false).unwrap();
        m.latents.pop();
        std::fs::write(out.join(META_FILE), serde_json::to_vec(&m).unwrap()).unwrap();
        let e = read_dataset(&out).unwrap_err().to_string();
        assert!(e.contains("1 latent series"), "{e}");
        let mut m = meta([2, 3, 1, 4, 4]);
        m.clip_start_times = Some(vec![0.0, -1.0]);
        std::fs::write(out.join(META_FILE), serde_json::to_vec(&m).unwrap()).unwrap();
        let e = read_dataset(&out).unwrap_err().to_string();
        assert!(e.contains("clip_start_times[1]"), "{e}");
        m.clip_start_times = Some(vec![0.0]);
        std::fs::write(out.join(META_FILE), serde_json::to_vec(&m).unwrap()).unwrap();
        let e = read_dataset(&out).unwrap_err().to_string();
        assert!(e.contains("1 clip_start_times"), "{e}");
        std::fs::remove_file(out.join(META_FILE)).unwrap();
        let e = read_dataset(&out).unwrap_err().to_string();
        assert!(e.contains("meta.json") && e.contains("missing"), "{e}");
        // The bare .npy still reads.
        assert!(read_dataset(&out.join(FRAMES_FILE)).unwrap().meta.is_none());
    }

    #[test]
    fn non_finite_frames_and_wrong_rank_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.npy");
        let mut bytes = Vec::new();
        write_npy(&mut bytes, &[2, 3], &[0.0; 6]).unwrap();
        std::fs::write(&p, &bytes).unwrap();
        assert!(read_dataset(&p).unwrap_err().to_string().contains("rank 2"));
        let mut data = vec![0.0f32; 24];
        data[13] = f32::NAN;
        let mut bytes = Vec::new();
        write_npy(&mut bytes, &[2, 3, 1, 2, 2], &data).unwrap();
        std::fs::write(&p, &bytes).unwrap();
        let e = read_dataset(&p).unwrap_err().to_string();
        assert!(e.contains("clip 1, frame 0") && e.contains("NaN"), "{e}");
    }
}
