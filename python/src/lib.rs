//! `physvid._core`: the generator and the estimator called from Python, in process, on the
//! workspace's typed library API (`generator::generate_in_memory` for a data set, `estimator::Request` and
//! `estimator::estimation_watched` for an estimate, `estimator::track` for the object's own
//! track). The Python package (`physvid/`) wraps
//! these functions in typed objects; errors arrive as the exception classes below, which mirror
//! `estimate`'s exit codes.

mod dataset;

use clap::Parser;
use estimator::cli::{EstimateArgs, ModelSpec};
use estimator::data::Frames;
use estimator::{estimation_watched, EstimateError, Watch};
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use std::ffi::OsString;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

create_exception!(_core, PhysvidError, PyException, "Any error of physvid.");
create_exception!(
    _core,
    BadInputError,
    PhysvidError,
    "The input or an option is unusable (estimate's exit code 2); the message names it and the fix."
);
create_exception!(
    _core,
    NoEstimateError,
    PhysvidError,
    "Training ran but gave no estimate (exit code 3)."
);
create_exception!(
    _core,
    UnreliableError,
    PhysvidError,
    "The answer's verdict is unreliable (exit code 4); args[1] is its report as JSON, args[2] the estimation."
);

/// `anyhow` from the library as the Python exception of its kind.
fn to_py(e: anyhow::Error) -> PyErr {
    let text = format!("{e:#}");
    match e.downcast_ref::<EstimateError>() {
        Some(EstimateError::NoEstimate(_)) => NoEstimateError::new_err(text),
        Some(inner) if inner.is_bad_input() => BadInputError::new_err(text),
        _ => PhysvidError::new_err(text),
    }
}

/// What an estimate reads: a path, or clips `[N, T, C, H, W]` of float32 in memory.
#[derive(FromPyObject)]
enum Source<'py> {
    Array(PyReadonlyArrayDyn<'py, f32>),
    Path(PathBuf),
}

impl Source<'_> {
    /// The request's input and, for an array, its clips (copied once, in memory), as the data
    /// set `meta` (its meta.json) describes where given.
    fn load(self, meta: Option<&str>) -> PyResult<(PathBuf, Option<Frames>)> {
        match self {
            Source::Path(p) => Ok((p, None)),
            Source::Array(a) => {
                let shape: [usize; 5] = a.shape().try_into().map_err(|_| {
                    BadInputError::new_err(format!(
                        "an array of shape {:?}: clips are [N, T, C, H, W]; reshape it",
                        a.shape()
                    ))
                })?;
                let data = a.as_array().iter().copied().collect();
                let frames = Frames::new(data, shape).map_err(BadInputError::new_err)?;
                let [n, t, c, h, w] = shape;
                let Some(meta) = meta else {
                    return Ok((format!("<array {n}×{t}×{c}×{h}×{w}>").into(), Some(frames)));
                };
                let meta: physvid_shared::DatasetMeta = serde_json::from_str(meta)
                    .map_err(|e| BadInputError::new_err(format!("meta.json: {e}")))?;
                let name: PathBuf =
                    format!("<data set {} {n}×{t}×{c}×{h}×{w}>", meta.scenario).into();
                let frames = frames
                    .with_meta(meta, &name)
                    .map_err(BadInputError::new_err)?;
                Ok((name, Some(frames)))
            }
        }
    }
}

/// A finished estimation: its report, and its clips for writing the files `estimate --out`
/// writes (held until the object goes).
#[pyclass(unsendable)]
struct Fitted {
    estimation: estimator::Estimation,
}

#[pymethods]
impl Fitted {
    /// report.json's text.
    fn report(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.estimation.report)
            .map_err(|e| PhysvidError::new_err(e.to_string()))
    }

    /// Writes what `estimate --out OUT [--force]` writes into `out`.
    #[pyo3(signature = (out, force=false))]
    fn save(&self, out: PathBuf, force: bool) -> PyResult<()> {
        let e = &self.estimation;
        let input = &e.report.run.config.input;
        estimator::output::check_out(&out, Some(input), force).map_err(|e| to_py(e.into()))?;
        estimator::output::write_outputs(&out, force, &e.data, &e.report)
            .map_err(|e| to_py(e.into()))
    }
}

/// `estimate`'s options that Python takes as keywords: every flag of the command line but the
/// input, the output's (Python's `out`, `Result.save` and `progress`) and a batch's (a Python
/// loop): as JSON, each with its keyword, flag, whether it takes a value and may repeat, its
/// default and its help, read from the one definition the command line parses
/// (`cli::EstimateArgs`).
#[pyfunction]
fn options() -> PyResult<String> {
    use clap::CommandFactory;
    const ELSEWHERE: [&str; 8] = [
        "input", "out", "force", "quiet", "batch", "shard", "merge", "help",
    ];
    let list: Vec<serde_json::Value> = EstimateArgs::command()
        .get_arguments()
        .filter(|a| a.get_long().is_some() && !ELSEWHERE.contains(&a.get_id().as_str()))
        .map(|a| {
            let takes = a.get_num_args().is_none_or(|n| n.takes_values())
                && !matches!(
                    a.get_action(),
                    clap::ArgAction::SetTrue | clap::ArgAction::SetFalse | clap::ArgAction::Count
                );
            serde_json::json!({
                "keyword": a.get_id().as_str(),
                "flag": format!("--{}", a.get_long().unwrap_or_default()),
                "takes_value": takes,
                "repeats": matches!(a.get_action(), clap::ArgAction::Append),
                "default": a.get_default_values().first().map(|v| v.to_string_lossy().into_owned()),
                "help": a.get_help().map(|h| h.to_string()).unwrap_or_default(),
            })
        })
        .collect();
    serde_json::to_string(&list).map_err(|e| PhysvidError::new_err(e.to_string()))
}

/// The typed request `estimate` runs for `source` (a data set's where `meta` is given) with
/// `args`, parsed and checked by the command line's own code, into `out` (the temporary folder,
/// never written, without it).
fn request_of(
    source: Source,
    meta: Option<&str>,
    args: Vec<String>,
    quiet: bool,
    out: Option<PathBuf>,
) -> PyResult<estimator::Request> {
    let (input, frames) = source.load(meta)?;
    let data_set = frames.as_ref().is_some_and(|f| f.meta.is_some());
    let mut line: Vec<OsString> = vec!["estimate".into(), input.into_os_string()];
    line.extend(args.into_iter().map(OsString::from));
    if quiet {
        line.push("--quiet".into());
    }
    // Without `out` nothing is written; the default folder is not asked to be writable.
    line.push("--out".into());
    line.push(out.unwrap_or_else(std::env::temp_dir).into_os_string());
    let parsed = EstimateArgs::try_parse_from(line).map_err(|e| {
        let text = e.to_string();
        let first = text.lines().next().unwrap_or_default();
        BadInputError::new_err(first.trim_start_matches("error: ").to_string())
    })?;
    let parsed = parsed.validate().map_err(|e| to_py(e.into()))?;
    let auto = matches!(parsed.model.model, Some(ModelSpec::Auto));
    let mut req = parsed.request().map_err(|e| to_py(e.into()))?;
    if data_set && !auto {
        // A data set's meta.json names its model, in memory as in its folder.
        if !req.candidates.is_empty() {
            return Err(BadInputError::new_err(
                "--candidate: tried only when the model is chosen: pass model=\"auto\"",
            ));
        }
        req.choose = false;
    }
    req.load.frames = frames.map(std::sync::Arc::new);
    Ok(req)
}

/// The typed request (as JSON) that `estimate` would run for `source` and `args`: every option
/// resolved to its value, defaults included; a refused option raises as `estimate` would.
#[pyfunction]
#[pyo3(signature = (source, args, meta=None))]
fn request(source: Source, args: Vec<String>, meta: Option<&str>) -> PyResult<String> {
    let req = request_of(source, meta, args, false, None)?;
    serde_json::to_string(&req).map_err(|e| PhysvidError::new_err(e.to_string()))
}

/// Estimates on `source` (a data set folder, a `.npy`, a video, an image folder, or a float32
/// array `[N, T, C, H, W]` read in memory: a data set's where `meta`, its meta.json, is given)
/// with `args`, `estimate`'s flags (what `options`
/// lists), parsed and resolved by the command line's own code (`cli::EstimateArgs`: the same
/// defaults, the same checks, the same errors), and returns the `Fitted` estimation; with
/// `out`, writes what `estimate --out OUT` writes. The GIL is released while it trains; Ctrl-C
/// stops it between epochs and raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (source, args, quiet=false, out=None, on_epoch=None, meta=None))]
fn estimate(
    py: Python<'_>,
    source: Source,
    args: Vec<String>,
    quiet: bool,
    out: Option<PathBuf>,
    on_epoch: Option<Py<PyAny>>,
    meta: Option<&str>,
) -> PyResult<Fitted> {
    let writes = out.is_some();
    let req = request_of(source, meta, args, quiet, out)?;
    if writes {
        estimator::output::check_out(&req.out, Some(req.input()), req.force)
            .map_err(|e| to_py(e.into()))?;
    }
    let cancel = AtomicBool::new(false);
    // Each epoch to the caller's function (epoch, its most, validation error, parameters by
    // name), called on the training's thread with the GIL taken while this one waits.
    let most = req.training.epochs;
    let report_epoch = |rec: &estimator::train::EpochRecord, names: &[&str]| {
        if let Some(f) = &on_epoch {
            Python::with_gil(|py| {
                let values: Vec<(&str, f64)> = names
                    .iter()
                    .copied()
                    .zip(rec.parameters.iter().copied())
                    .collect();
                let args = (rec.epoch, most, rec.val_rel_mse, values);
                if let Err(e) = f.call1(py, args) {
                    e.print(py);
                }
            });
        }
    };
    let watch = Watch {
        epoch: on_epoch.as_ref().map(|_| &report_epoch as _),
        cancel: Some(&cancel),
    };
    let (result, interrupted) = std::thread::scope(|s| {
        let run = s.spawn(|| estimation_watched(&req, watch));
        let mut interrupted = None;
        while !run.is_finished() {
            py.allow_threads(|| std::thread::sleep(Duration::from_millis(50)));
            if let Err(e) = py.check_signals() {
                cancel.store(true, Ordering::Relaxed);
                interrupted = Some(e);
            }
        }
        (run.join(), interrupted)
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    let estimation = result
        .map_err(|_| PhysvidError::new_err("the estimation panicked"))?
        .map_err(to_py)?;
    let fitted = Fitted { estimation };
    if writes {
        fitted.save(req.out.clone(), req.force)?;
    }
    if fitted.estimation.report.verdict.grade == estimator::verdict::Grade::Unreliable {
        let json = fitted.report()?;
        let message = "the answer is unreliable (the verdict's reasons are in the report)";
        let fitted = Py::new(py, fitted)?;
        return Err(UnreliableError::new_err((message, json, fitted)));
    }
    Ok(fitted)
}

/// The object's own track in the video file `video` (trimmed to `start`..`end` of its own
/// timeline, at `fps` frames a second of real time where given), with each law fitted where it
/// holds, as report.json's `track`; `None` where nothing lives long enough to follow.
#[pyfunction]
#[pyo3(signature = (video, start=None, end=None, fps=None))]
fn track(
    py: Python<'_>,
    video: PathBuf,
    start: Option<f64>,
    end: Option<f64>,
    fps: Option<f64>,
) -> PyResult<Option<String>> {
    if !video.is_file() || !physvid_shared::video::is_recording(&video) {
        return Err(BadInputError::new_err(format!(
            "{}: not a video file; track() reads a recording (an .mp4, .mov, .avi, .gif, ...)",
            video.display()
        )));
    }
    let route = py
        .allow_threads(|| estimator::track::follow_file(&video, (start, end), fps))
        .map_err(|e| BadInputError::new_err(format!("{}: {e}", video.display())))?;
    route
        .map(|r| serde_json::to_string(&r).map_err(|e| PhysvidError::new_err(e.to_string())))
        .transpose()
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(dataset::generate, m)?)?;
    m.add_function(wrap_pyfunction!(dataset::save, m)?)?;
    m.add_function(wrap_pyfunction!(request, m)?)?;
    m.add_function(wrap_pyfunction!(estimate, m)?)?;
    m.add_function(wrap_pyfunction!(track, m)?)?;
    m.add_function(wrap_pyfunction!(options, m)?)?;
    m.add_class::<Fitted>()?;
    let py = m.py();
    m.add("PhysvidError", py.get_type::<PhysvidError>())?;
    m.add("BadInputError", py.get_type::<BadInputError>())?;
    m.add("NoEstimateError", py.get_type::<NoEstimateError>())?;
    m.add("UnreliableError", py.get_type::<UnreliableError>())?;
    Ok(())
}
