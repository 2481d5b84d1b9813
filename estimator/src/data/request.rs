//! What to load, part of the typed request (`config::Request`, made from the command line by
//! `cli::EstimateArgs::request`): the data layer sits below the CLI and never reads its types.

use super::framing::Framing;
use crate::physics::model::by_source;
use crate::physics::ModelRef;
use physvid_shared::video::fields::FieldsChoice;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The input and the flags that decide how it becomes clips.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LoadRequest {
    /// A `gen` data set directory, a `.npy`, a video or an image folder.
    pub input: PathBuf,
    /// `--model`, when given (a data set's meta.json may name it instead).
    #[serde(serialize_with = "by_source::option")]
    pub model: Option<ModelRef>,
    /// `model` is one candidate of a choice: a data set's meta.json may name another (its
    /// ground truth is then compared by name where the names agree).
    pub trying: bool,
    /// `--dt`, when given.
    pub dt: Option<f64>,
    pub recording: RecordingRequest,
    /// Clips held in memory by a library caller (a Python array or data set): read instead of
    /// `input`, which then only names them in messages, like a bare `.npy` (no meta.json: `dt`
    /// and the model given, or the model chosen) or, with their meta.json, like a data set's
    /// folder. Never serialised.
    #[serde(skip)]
    pub frames: Option<std::sync::Arc<Frames>>,
}

/// Clips `[N, T, C, H, W]` of float32 in memory: a bare array's, or a `gen` data set's with
/// its meta.json (`meta`), read as its folder would be.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frames {
    pub data: Vec<f32>,
    pub shape: [usize; 5],
    pub meta: Option<physvid_shared::DatasetMeta>,
}

impl Frames {
    /// `data` as clips of `shape`, where their lengths agree.
    pub fn new(data: Vec<f32>, shape: [usize; 5]) -> Result<Frames, String> {
        let want = shape.iter().try_fold(1usize, |a, &b| a.checked_mul(b));
        if want != Some(data.len()) {
            return Err(format!(
                "clips of shape {shape:?} hold {} values, not {}",
                want.map_or("too many".into(), |w| w.to_string()),
                data.len()
            ));
        }
        Ok(Frames {
            data,
            shape,
            meta: None,
        })
    }

    /// These clips as the data set `meta` describes (checked against their shape as a data
    /// set's folder is; `name` stands for its folder in messages).
    pub fn with_meta(
        self,
        meta: physvid_shared::DatasetMeta,
        name: &std::path::Path,
    ) -> Result<Frames, String> {
        let meta_path = name.join(physvid_shared::dataset::META_FILE);
        physvid_shared::dataset::validate_meta(&meta, &meta_path, name, self.shape)
            .map_err(|e| e.to_string())?;
        Ok(Frames {
            meta: Some(meta),
            ..self
        })
    }
}

/// A constant acceleration found on the object's track, as a descent reads it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TrackedMotion {
    /// Where the law holds, seconds of the file's timeline.
    pub span: (f64, f64),
    /// The release (the vertex along the acceleration), seconds of the file's timeline, where
    /// the track saw it.
    pub release: Option<f64>,
    /// The acceleration's direction in the displayed picture (a unit vector, y down): the line
    /// a descent's positions are read along where the path's own is another (a toss's path
    /// bends; its fall is along the acceleration).
    pub axis: [f64; 2],
    /// How far it moves over the span, as a share of the picture's larger side.
    pub travel: f64,
    /// The track saw the object move, by more than its own size, before the release (a toss's
    /// rise): what comes before the release is no rest, and a reading there is not taken at it.
    pub moving_before: bool,
    /// The rectangle of the displayed frame the object keeps to over the span: a fall's or a
    /// slide's frames where no `--crop` is given (not where the picture moves most: a hand
    /// beside a toss); other models keep their own framing.
    pub frame: Option<physvid_shared::video::Crop>,
}

/// A fall's acceleration lies within this many degrees of the picture's vertical (a camera is
/// levelled within a few: the shared drop's and toss's lie 1.4° and 1.7° off it; a ramp seen
/// from the side shows its slope: the shared rolls' lie 68° and 71° off; one steeper than 60°
/// is all but a fall); further off, a slide, a roll or a cart pulled along a level track.
pub const FALL_DEG: f64 = 30.0;

/// Whether an acceleration drawn along `axis` (the picture's, y down) is a fall's
/// ([`FALL_DEG`]), not a slide's.
pub fn falls(axis: [f64; 2]) -> bool {
    (axis[1].atan2(axis[0]).to_degrees() - 90.0).abs() <= FALL_DEG
}

impl TrackedMotion {
    /// Whether its acceleration is a fall's (`falls`), not a slide's.
    pub fn falls(&self) -> bool {
        falls(self.axis)
    }
}

/// A recording's flags: decoding, framing and cutting into clips. Their model-dependent
/// defaults (Table 5's clip) are resolved in `data::recording` once the model is known.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct RecordingRequest {
    /// `--fps`: frames per second of real time, overriding the container's.
    pub fps: Option<f64>,
    /// `--crop` (`None`: auto).
    pub crop: Option<Framing>,
    /// `--start` / `--end`: the part kept, in seconds of the file's timeline.
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// `--size`: the encoder's frame size (width, height); `None`: chosen from the framed
    /// region's shape (`framing::default_size`).
    pub size: Option<(usize, usize)>,
    pub frames_per_clip: Option<usize>,
    pub stride: Option<usize>,
    pub hop: Option<usize>,
    /// `--preview`: write clips.png.
    pub preview: bool,
    /// `--fields`: how an interlaced recording's fields are read.
    pub fields: FieldsChoice,
    /// The `--reference` times (seconds of the file's timeline): frames the user measured the
    /// system at, which the free motion found in the frames is taken to include.
    pub measured_at: Vec<f64>,
    /// A constant acceleration the object's track holds (`guide::measured`): a descent's
    /// release and line read from it in place of the picture's.
    #[serde(default)]
    pub tracked: Option<TrackedMotion>,
    /// The camera's shake the object's track measured (`guide::steadied`): each frame moved
    /// back by it before the encoder sees it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shake: Option<super::CameraShake>,
    /// The recording flags given, as written (a data set refuses them by name).
    pub given: Vec<String>,
}
