//! Recordings as input: the flags that turn a video or a folder of images into clips
//! (`RecordingFlags`), their parsers, and `load_recording`, which decodes through
//! `physvid_shared::video` (ffmpeg) and cuts the frames into clips.

use crate::config::ModelKind;
use crate::error::{input_error, EstimateError};
use physvid_shared::contact_sheet::{contact_sheet, encode_png};
use physvid_shared::video::{self, Crop, VideoInfo, VideoOptions};
use serde::Serialize;
use std::path::Path;

/// At most this many clips by default: the hop between clip starts grows to stay below it.
pub const MAX_DEFAULT_CLIPS: usize = 1000;

/// How a recording becomes clips (ignored for datasets).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordingFlags {
    /// Frames per second of real time (overrides the container's; required for image folders).
    pub fps: Option<f64>,
    pub crop: Option<Crop>,
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// Frame size fed to the encoder (width, height).
    pub size: (usize, usize),
    /// Frames per clip (default: appendix Table 5's for the model).
    pub frames_per_clip: Option<usize>,
    /// Recording frames between clip frames (default: Table 5's dt × fps, at least 1).
    pub stride: Option<usize>,
    /// Recording frames between clip starts (default: 1, or more to stay within 1000 clips).
    pub hop: Option<usize>,
    /// Write clips.png, the clips as the model sees them.
    pub preview: bool,
}

impl Default for RecordingFlags {
    fn default() -> Self {
        RecordingFlags {
            fps: None,
            crop: None,
            start: None,
            end: None,
            size: (100, 56),
            frames_per_clip: None,
            stride: None,
            hop: None,
            preview: false,
        }
    }
}

/// Parses `--crop X,Y,W,H`.
pub fn parse_crop(text: &str) -> Result<Crop, String> {
    let v: Vec<usize> = text
        .split(',')
        .map(|p| p.trim().parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{text}' is not X,Y,W,H in pixels (e.g. 100,0,400,300)"))?;
    match v[..] {
        [x, y, w, h] if w > 0 && h > 0 => Ok(Crop { x, y, w, h }),
        _ => Err(format!(
            "'{text}' is not X,Y,W,H with W, H > 0 (e.g. 100,0,400,300)"
        )),
    }
}

/// Parses `--size WxH`.
pub fn parse_size(text: &str) -> Result<(usize, usize), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{text}' is not WxH (e.g. 100x56)"))?;
    match (w.trim().parse::<usize>(), h.trim().parse::<usize>()) {
        (Ok(w), Ok(h)) if (4..=4096).contains(&w) && (4..=4096).contains(&h) => Ok((w, h)),
        _ => Err(format!(
            "'{text}' is not WxH with 4 ≤ W, H ≤ 4096 (e.g. 100x56)"
        )),
    }
}

impl RecordingFlags {
    /// Checks the flags that do not depend on the recording.
    pub fn validate(&self) -> Result<(), EstimateError> {
        if let Some(f) = self.fps {
            if !(f.is_finite() && f > 0.0) {
                return Err(input_error(format!("--fps {f}: must be > 0")));
            }
        }
        for (flag, v) in [("--start", self.start), ("--end", self.end)] {
            if let Some(v) = v {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(input_error(format!("{flag} {v}: must be a time >= 0 s")));
                }
            }
        }
        if let (Some(s), Some(e)) = (self.start, self.end) {
            if e <= s {
                return Err(input_error(format!(
                    "--end {e} is not after --start {s}: zero frames would remain"
                )));
            }
        }
        if self.frames_per_clip.is_some_and(|t| t < 3) {
            return Err(input_error(
                "--frames-per-clip: at least 3 (two to start a rollout, one to predict)",
            ));
        }
        if self.stride == Some(0) || self.hop == Some(0) {
            return Err(input_error("--stride and --hop: at least 1 frame"));
        }
        Ok(())
    }
}

/// What was made of a recording, for the report and the plots.
#[derive(Debug, Clone, Serialize)]
pub struct RecordingSummary {
    pub info: VideoInfo,
    /// The frame rate used and where it came from ("--fps" or "container").
    pub fps: f64,
    pub fps_source: &'static str,
    pub frames_decoded: usize,
    pub frames_per_clip: usize,
    pub stride: usize,
    pub hop: usize,
    pub clips: usize,
    pub size: (usize, usize),
    pub crop: Option<Crop>,
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// Seconds spent decoding (ffmpeg, the pipe, crop and resize) and frames per second.
    pub decode_s: f64,
    pub decode_fps: f64,
    /// First recording frame of each clip (index into the decoded frames).
    #[serde(skip)]
    pub clip_starts: Vec<usize>,
}

/// A decoded recording cut into clips (by index: the frames are held once).
pub struct LoadedRecording {
    /// Every decoded frame, [F, H·W] row-major, values in [0, 1].
    pub frames: Vec<f32>,
    /// The recording frame of every clip frame, [N·T].
    pub clip_index: Vec<i64>,
    /// [N, T, 1, H, W] of the clips.
    pub shape: [usize; 5],
    pub dt: f64,
    /// clips.png for `--preview`.
    pub preview_png: Option<Vec<u8>>,
    pub summary: RecordingSummary,
    pub warnings: Vec<String>,
}

/// Decodes `input` for `model` and cuts it into clips.
pub fn load_recording(
    input: &Path,
    model: ModelKind,
    flags: &RecordingFlags,
) -> Result<LoadedRecording, EstimateError> {
    let (table_frames, table_dt) = model.table5_clip();
    let frames_per_clip = flags.frames_per_clip.unwrap_or(table_frames);
    let mut warnings = Vec::new();
    // The frame rate first (cheap), for the default stride.
    let info = if input.is_dir() {
        None
    } else {
        Some(video::probe(input)?)
    };
    let (fps, fps_source) = match (flags.fps, info.as_ref().and_then(|i| i.container_fps)) {
        (Some(f), _) => (f, "--fps"),
        (None, Some(f)) => (f, "container"),
        (None, None) => {
            return Err(input_error(format!(
                "{}: no frame rate known (an image folder, or a container without one): pass --fps",
                input.display()
            )))
        }
    };
    if let (None, Some(i)) = (flags.fps, &info) {
        if let (Some(capture), Some(container)) = (i.capture_fps, i.container_fps) {
            if (capture / container - 1.0).abs() > 0.01 {
                warnings.push(format!(
                    "the container says {container:.3} fps but the file's com.android.capture.fps \
                     tag says {capture} fps (a slow-motion capture?): dt, and every rate, is wrong \
                     by {:.2}× unless you pass --fps {capture}",
                    capture / container
                ));
            }
        }
    }
    let stride = flags
        .stride
        .unwrap_or_else(|| ((table_dt * fps).round() as usize).max(1));
    let opts = VideoOptions {
        fps: Some(fps),
        crop: flags.crop,
        start: flags.start,
        end: flags.end,
        size: flags.size,
        frames_per_clip,
        stride,
        hop: flags.hop,
        max_clips: MAX_DEFAULT_CLIPS,
    };
    let started = std::time::Instant::now();
    let decoded = video::decode(input, &opts, info)?;
    let decode_s = started.elapsed().as_secs_f64();
    let n = decoded.clip_starts.len();
    let shape = [n, frames_per_clip, 1, flags.size.1, flags.size.0];
    // Four clips spread over the recording, at the encoder's resolution, magnified 2×.
    let preview_png = flags.preview.then(|| {
        let m = n.min(4);
        let rows: Vec<usize> = (0..m).map(|k| k * (n - 1) / (m - 1).max(1)).collect();
        let (clips, shape) = decoded.clips(&rows, frames_per_clip, stride);
        let all: Vec<usize> = (0..rows.len()).collect();
        encode_png(&contact_sheet(&clips, shape, &all, 2))
    });
    let summary = RecordingSummary {
        info: decoded.info.clone(),
        fps,
        fps_source,
        frames_decoded: decoded.frame_count(),
        frames_per_clip,
        stride,
        hop: decoded.hop,
        clips: decoded.clip_starts.len(),
        size: flags.size,
        crop: flags.crop,
        start: flags.start,
        end: flags.end,
        decode_s,
        decode_fps: decoded.frame_count() as f64 / decode_s.max(1e-9),
        clip_starts: decoded.clip_starts.clone(),
    };
    if summary.clips < 2 {
        return Err(input_error(format!(
            "{}: only {} clip of {frames_per_clip} frames at stride {stride} fits in {} frames; \
             at least 2 are needed (lower --frames-per-clip, --stride or --hop, or trim less)",
            input.display(),
            summary.clips,
            summary.frames_decoded
        )));
    }
    Ok(LoadedRecording {
        clip_index: decoded.clip_index(frames_per_clip, stride),
        shape,
        dt: decoded.dt(stride),
        frames: decoded.frames,
        preview_png,
        summary,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crop_and_size_parse_or_say_what_is_expected() {
        assert_eq!(
            parse_crop("1,2,30,40").unwrap(),
            Crop {
                x: 1,
                y: 2,
                w: 30,
                h: 40
            }
        );
        assert!(parse_crop("1,2,0,4").unwrap_err().contains("X,Y,W,H"));
        assert!(parse_crop("1,2,3").is_err());
        assert_eq!(parse_size("100x56").unwrap(), (100, 56));
        assert!(parse_size("100").unwrap_err().contains("WxH"));
        assert!(parse_size("2x2").is_err());
    }
}
