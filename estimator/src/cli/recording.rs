//! The recording flags: how a video or an image folder becomes clips (frame rate, crop, trim,
//! size, clip length, stride, hop). Their model-dependent defaults (Table 5's clip) are
//! resolved in `data::recording`.

use crate::data::{Framing, RecordingRequest, DEFAULT_SIZE};
use crate::error::{input_error, EstimateError};
use crate::physics::MODELS;
use physvid_shared::cli::num;
use physvid_shared::video::fields::FieldsChoice;
use physvid_shared::video::Crop;
use serde::Serialize;

/// The highest frame rate taken (the fastest scientific cameras film ten million frames a
/// second).
pub const MAX_FPS: f64 = 1e7;

/// How a recording becomes clips (refused for datasets).
#[derive(Debug, Clone, PartialEq, Serialize, clap::Args)]
#[command(next_help_heading = "Recordings")]
pub struct RecordingArgs {
    /// Frames per second of real time [default: a slow-motion file's capture tag
    /// (com.android.capture.fps: 120 where the container says 30), else the container's, else
    /// the frames' timestamps']; required for an image folder. An interlaced recording (its
    /// rows comb where it moves) is read as its fields, at twice this rate.
    #[arg(long)]
    pub fps: Option<f64>,
    /// What part of the frame the encoder sees: X,Y,W,H in pixels of the displayed (rotated)
    /// frame (W, H ≥ 4); `full` for the whole frame; `auto` (the default for videos) for the
    /// region where the picture moves, found by a quick low-resolution pass (an object that
    /// crosses once, as a fall, along its whole way; report.html shows it; an image folder
    /// keeps its whole frame). Without --crop, where the object's track guides the run (see
    /// --model), the object's path over the track's span.
    #[arg(long, value_parser = parse_crop, value_name = "X,Y,W,H|auto|full")]
    pub crop: Option<Framing>,
    /// First second to use (of the file's own timeline) [default: where the motion starts:
    /// still frames before it, held half a second or more, are left out]. For sliding-block
    /// and free-fall the release from rest is found in the frames, and without --start/--end
    /// only the descent is kept (from just before the release to the impact).
    #[arg(long)]
    pub start: Option<f64>,
    /// Last second to use [default: one clip's span after the motion settles].
    #[arg(long)]
    pub end: Option<f64>,
    #[arg(long, value_parser = parse_size, value_name = "WxH", help = format!(
        "Frame size fed to the encoder (grey, area-averaged) [default: {}x{}, or as many \
         pixels at the frame's (or the crop's) shape where it is taller than wide]",
        DEFAULT_SIZE.0, DEFAULT_SIZE.1
    ))]
    pub size: Option<(usize, usize)>,
    #[arg(long, help = frames_help())]
    pub frames_per_clip: Option<usize>,
    /// Recording frames between clip frames, so dt = stride / fps [default: Table 5's dt × fps,
    /// e.g. 6 for the pendulum at 60 fps, shortened with a warning where a clip would span more
    /// than half of the frames kept; with the model chosen, one for every candidate: a clip of
    /// 20 frames spans the motion's period, else half the frames kept].
    #[arg(long)]
    pub stride: Option<usize>,
    /// Recording frames between the starts of consecutive clips [default: 1, or more to stay
    /// within 1000 clips].
    #[arg(long)]
    pub hop: Option<usize>,
    /// Also write clips.png, the first clips as the model sees them (check crop and stride).
    #[arg(long)]
    pub preview: bool,
    /// How an interlaced recording (two fields a frame, taken half an interval apart) is read:
    /// `auto` finds the fields from the picture (a moving region's rows comb) or the
    /// container's tag and reads each as a frame, at twice the rate; `frames` never splits;
    /// `top-first` / `bottom-first` split in that order [default: auto].
    #[arg(long, value_enum, value_name = "auto|frames|top-first|bottom-first")]
    pub fields: Option<FieldsChoice>,
}

fn frames_help() -> String {
    let each: Vec<String> = MODELS
        .iter()
        .map(|m| format!("{} {}", m.name(), m.table5_clip().0))
        .collect();
    format!(
        "Frames per clip [default: appendix Table 5's for the model: {}]",
        each.join(", ")
    )
}

/// Parses `--crop X,Y,W,H|auto|full`.
pub fn parse_crop(text: &str) -> Result<Framing, String> {
    match text.trim() {
        "auto" => return Ok(Framing::Auto),
        "full" => return Ok(Framing::Full),
        _ => {}
    }
    let v: Vec<usize> = text
        .split(',')
        .map(|p| p.trim().parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{text}' is not X,Y,W,H in pixels (e.g. 100,0,400,300)"))?;
    match v[..] {
        [x, y, w, h] if w >= 4 && h >= 4 => Ok(Framing::Crop(Crop { x, y, w, h })),
        [_, _, _, _] => Err(format!(
            "'{text}': a crop of W, H ≥ 4 pixels is needed to show a motion (e.g. 100,0,400,300)"
        )),
        _ => Err(format!(
            "'{text}' is not X,Y,W,H in pixels (e.g. 100,0,400,300)"
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

impl RecordingArgs {
    /// The flags as the data layer reads them (the frame size resolved).
    pub fn request(&self) -> RecordingRequest {
        RecordingRequest {
            fps: self.fps,
            crop: self.crop,
            start: self.start,
            end: self.end,
            size: self.size,
            frames_per_clip: self.frames_per_clip,
            stride: self.stride,
            hop: self.hop,
            preview: self.preview,
            fields: self.fields.unwrap_or_default(),
            given: self.given(),
            measured_at: Vec::new(),
            tracked: None,
            shake: None,
        }
    }

    /// The recording flags given, as written on the command line.
    pub fn given(&self) -> Vec<String> {
        [
            ("fps", self.fps.is_some()),
            ("crop", self.crop.is_some()),
            ("start", self.start.is_some()),
            ("end", self.end.is_some()),
            ("size", self.size.is_some()),
            ("frames_per_clip", self.frames_per_clip.is_some()),
            ("stride", self.stride.is_some()),
            ("hop", self.hop.is_some()),
            ("preview", self.preview),
            ("fields", self.fields.is_some()),
        ]
        .into_iter()
        .filter(|&(_, given)| given)
        .map(|(id, _)| super::flag_name(id))
        .collect()
    }

    /// Checks the flags that do not depend on the recording.
    pub fn validate(&self) -> Result<(), EstimateError> {
        if let Some(f) = self.fps {
            if !(f > 0.0 && f <= MAX_FPS) {
                return Err(input_error(format!(
                    "--fps {}: must be > 0 and at most {MAX_FPS:e} (frames per second of real time)",
                    num(f)
                )));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flags_given_are_named_as_written() {
        use clap::Parser;
        let args = crate::EstimateArgs::try_parse_from([
            "estimate",
            "clip.mp4",
            "--fps",
            "30",
            "--start",
            "1",
            "--frames-per-clip",
            "10",
            "--preview",
        ])
        .unwrap();
        assert_eq!(
            args.recording.given(),
            ["--fps", "--start", "--frames-per-clip", "--preview"]
        );
    }

    #[test]
    fn crop_and_size_parse_or_say_what_is_expected() {
        assert_eq!(
            parse_crop("1,2,30,40").unwrap(),
            Framing::Crop(Crop {
                x: 1,
                y: 2,
                w: 30,
                h: 40
            })
        );
        assert_eq!(parse_crop("auto").unwrap(), Framing::Auto);
        assert_eq!(parse_crop("full").unwrap(), Framing::Full);
        assert!(parse_crop("1,2,0,4").unwrap_err().contains("W, H ≥ 4"));
        // A 1×1 crop used to be stretched to the frame size and trained on.
        assert!(parse_crop("10,10,1,1").unwrap_err().contains("W, H ≥ 4"));
        assert!(parse_crop("1,2,3").is_err());
        assert_eq!(parse_size("100x56").unwrap(), (100, 56));
        assert!(parse_size("100").unwrap_err().contains("WxH"));
        assert!(parse_size("2x2").is_err());
    }
}
