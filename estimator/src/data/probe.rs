//! The input probed before any frame is read: a data set's meta.json and its array's header, or
//! a recording's container (ffprobe) and the recording flags. The model, dt and how a recording
//! is cut in time are settled here, so the configuration is resolved once, before the load
//! (`config::RunConfig::resolve`), and a bad flag is refused before minutes of decoding.

use super::{dataset, timing, LoadRequest};
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::video::fields::FieldsChoice;
use physvid_shared::video::{self, is_recording, VideoInfo};
use physvid_shared::{DatasetHeader, DatasetMeta};

/// What the probe settled: the model and dt (which the configuration alone carries from here
/// on), and the plan the load follows.
#[derive(Debug, Clone)]
pub struct Probe {
    pub model: ModelRef,
    /// Seconds between a clip's frames: `--dt` or meta.json's; a recording's `stride / fps`.
    pub dt: f64,
    pub plan: Plan,
}

/// What the load reads besides the flags, by kind of input.
#[derive(Debug, Clone, PartialEq)]
pub enum Plan {
    /// A `gen` data set or a bare `.npy`: its header and metadata, checked (the frames are
    /// read from it by the load).
    Dataset(Box<DatasetHeader>),
    /// A video or an image folder.
    Recording(RecordingPlan),
}

impl Plan {
    /// A data set's metadata (its calibration, its ground truth).
    pub fn meta(&self) -> Option<&DatasetMeta> {
        match self {
            Plan::Dataset(header) => header.meta.as_ref(),
            Plan::Recording(_) => None,
        }
    }
}

/// A recording in time, before decoding: its frame rate and where that came from, and the clip
/// its model asks for (Table 5's, or the flags').
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingPlan {
    /// The container's facts (`None`: an image folder).
    pub info: Option<VideoInfo>,
    pub fps: f64,
    pub fps_source: &'static str,
    pub frames_per_clip: usize,
    pub stride: usize,
    /// What these choices say to the user (a capture tag's rate, a stride shortened).
    pub warnings: Vec<String>,
}

/// Probes `req.input` (its kind checked first) for the model, dt and the load's plan; clips in
/// memory (`req.frames`) as a bare `.npy`.
pub fn probe(req: &LoadRequest) -> Result<Probe, EstimateError> {
    if req.frames.is_some() {
        return dataset::probe(req);
    }
    physvid_shared::input::check_kind(&req.input).map_err(input_error)?;
    if is_recording(&req.input) {
        recording(req)
    } else {
        dataset::probe(req)
    }
}

/// A video or an image folder: `--model` needed, `--dt` refused (dt is `stride / fps`).
fn recording(req: &LoadRequest) -> Result<Probe, EstimateError> {
    let input = &req.input;
    if !input.exists() {
        return Err(input_error(format!(
            "{}: no such file or directory",
            input.display()
        )));
    }
    if input.is_dir() && video::image_files(input).is_ok_and(|f| f.is_empty()) {
        return Err(input_error(format!(
            "{}: a directory that is neither a gen dataset (no frames.npy or meta.json) nor an \
             image folder (no .png, .jpg or .jpeg files)",
            input.display()
        )));
    }
    let model = req.model.ok_or_else(|| {
        input_error(format!(
            "{}: a recording needs --model (e.g. --model pendulum)",
            input.display()
        ))
    })?;
    if req.dt.is_some() {
        return Err(input_error(format!(
            "--dt: {} is read as a recording (a video or an image folder), whose dt is \
             --stride / fps; set those instead",
            input.display()
        )));
    }
    let flags = &req.recording;
    let (table_frames, table_dt) = model.table5_clip();
    let frames_per_clip = flags.frames_per_clip.unwrap_or(table_frames);
    let mut warnings = Vec::new();
    if input.is_dir() && flags.fields != FieldsChoice::Auto {
        return Err(input_error(format!(
            "--fields: {} is an image folder, whose images are whole frames; --fields reads \
             a video's fields",
            input.display()
        )));
    }
    let info = if input.is_dir() {
        None
    } else {
        Some(video::probe_as(input, flags.fields)?)
    };
    let (fps, fps_source) = timing::frame_rate(input, info.as_ref(), flags, &mut warnings)?;
    let stride = timing::stride(
        flags.stride,
        info.as_ref(),
        (flags.start, flags.end),
        (frames_per_clip, table_dt, fps),
        model,
        &mut warnings,
    );
    Ok(Probe {
        model,
        dt: stride as f64 / fps,
        plan: Plan::Recording(RecordingPlan {
            info,
            fps,
            fps_source,
            frames_per_clip,
            stride,
            warnings,
        }),
    })
}
