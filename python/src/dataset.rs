//! A `gen` data set between Rust and Python: rendered in memory (`generate`: frames as a
//! numpy array, meta.json, preview.png) and written as `gen` writes it (`save`).

use crate::{BadInputError, PhysvidError};
use numpy::ndarray::Ix5;
use numpy::{PyArray, PyArrayMethods, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;

/// A data set in memory as Python receives it: frames, meta.json, preview.png.
type InMemoryParts<'py> = (Bound<'py, PyArray<f32, Ix5>>, String, Bound<'py, PyBytes>);

/// The data set `gen ARGS` writes, rendered in memory (seeded: the same bytes once saved):
/// its frames `[N, T, C, H, W]`, its meta.json and its preview.png. Nothing is written.
#[pyfunction]
pub fn generate<'py>(py: Python<'py>, args: Vec<String>) -> PyResult<InMemoryParts<'py>> {
    // `gen` asks for a writable --out; nothing is written to it.
    let out = std::env::temp_dir().display().to_string();
    let mut line: Vec<&str> = args.iter().map(String::as_str).collect();
    line.extend(["--out", &out]);
    let cfg = generator::GenArgs::config_from(&line)
        .map_err(|e| BadInputError::new_err(e.to_string()))?;
    let data = py
        .allow_threads(|| generator::generate_in_memory(&cfg))
        .map_err(|e| BadInputError::new_err(format!("{e:#}")))?;
    let meta = serde_json::to_string_pretty(&data.meta)
        .map_err(|e| PhysvidError::new_err(e.to_string()))?;
    let frames = PyArray::from_vec(py, data.frames).reshape(data.meta.shape)?;
    Ok((frames, meta, PyBytes::new(py, &data.preview)))
}

/// Writes a data set held in memory (`generate`'s three parts) into `folder`, as `gen --out
/// FOLDER` writes it (`force`: into a folder this tool did not make).
#[pyfunction]
#[pyo3(signature = (frames, meta, preview, folder, force=false))]
pub fn save(
    py: Python<'_>,
    frames: PyReadonlyArrayDyn<'_, f32>,
    meta: &str,
    preview: Vec<u8>,
    folder: PathBuf,
    force: bool,
) -> PyResult<()> {
    let meta = serde_json::from_str(meta).map_err(|e| BadInputError::new_err(e.to_string()))?;
    let data = generator::InMemory {
        frames: frames.as_array().iter().copied().collect(),
        meta,
        preview,
    };
    py.allow_threads(|| data.save(&folder, force))
        .map_err(|e| BadInputError::new_err(format!("{e:#}")))?;
    Ok(())
}
