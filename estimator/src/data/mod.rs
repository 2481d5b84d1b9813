//! `ClipData`: a dataset (or a recording cut into clips) loaded onto the training device as one
//! tensor, split 80/20 into training and validation clips, with the ground truth. The input is
//! probed first (`probe`: the model, dt and the load's plan, which the configuration takes
//! over), then loaded as the configuration says (`load_clips`).

mod crowd;
mod dataset;
pub mod descent;
mod framing;
mod hue;
pub mod kept;
pub mod object;
pub mod perspective;
pub mod photometric;
mod probe;
pub mod recording;
mod request;
mod reuse;
mod scale;
mod shake;
mod stillness;
pub mod summary;
mod swing;
mod timing;
mod tinted;
mod tracked;

pub use framing::{Framing, DEFAULT_SIZE};
pub use probe::{probe, Plan, Probe, RecordingPlan};
pub use request::{falls, Frames, LoadRequest, RecordingRequest, TrackedMotion, FALL_DEG};
pub use shake::{largest_shift, CameraShake};

use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::cli::num;
use physvid_shared::DatasetMeta;
pub use reuse::survey as shared_survey;
use std::collections::BTreeMap;
use summary::RecordingSummary;
use tch::{Device, Kind, Tensor};

/// Clips ready for training.
#[derive(Debug)]
pub struct ClipData {
    /// Training clips [N_train, T, D] (D = C·H·W), on the device.
    pub train: Tensor,
    /// Validation clips [N_val, T, D]: the last 20 % of the file, no shuffling.
    pub val: Tensor,
    /// Each training / validation clip's start time since the release (s) \[N\], when meta.json
    /// gives `clip_start_times` (systems released from rest at the start of the recording).
    pub train_start: Option<Tensor>,
    pub val_start: Option<Tensor>,
    /// The start times before the release are on the law's rise toward it (a toss,
    /// `Descent::rising`), not at rest.
    pub rising: bool,
    pub frames_per_clip: i64,
    pub inputs: i64,
    pub shape: [usize; 5],
    /// True parameter values by name, when the metadata gives them.
    pub truth: BTreeMap<String, f64>,
    pub meta: Option<DatasetMeta>,
    /// For a recording: what was decoded, and every frame standardised like the clips
    /// [1, F, D] (for the latent over the whole recording).
    pub recording: Option<(RecordingSummary, Tensor)>,
    /// Things about the input the report should say (e.g. a doubtful frame rate).
    pub warnings: Vec<String>,
    /// For a recording: its first clips as the model sees them (in report.html, and clips.png
    /// with `--preview`).
    pub preview_png: Option<Vec<u8>>,
    /// The light's drift divided out of the frames, where it was (see `photometric`).
    pub photometric: Option<photometric::Photometric>,
    /// The mean training frame [D] in the clips' standardised units (its mean divided by the
    /// spread): a clip frame plus it is the frame as loaded, up to one scale.
    pub background: Tensor,
}

impl ClipData {
    /// A recording's descent's line, as the centroid encoder reads positions along it.
    pub fn line(&self) -> Option<crate::encoder::centroid::Line> {
        self.recording
            .as_ref()
            .and_then(|(s, _)| s.descent)
            .map(|d| d.line)
    }

    /// How a recording's moving object was found (`data::object`), and the centroid encoder
    /// locates it too (on the frames themselves where none was found).
    pub fn object_located(&self) -> crate::encoder::centroid::Located {
        self.recording
            .as_ref()
            .and_then(|(s, _)| s.object)
            .map_or_else(Default::default, |o| o.located)
    }

    pub fn n_train(&self) -> i64 {
        self.train.size()[0]
    }

    pub fn n_val(&self) -> i64 {
        self.val.size()[0]
    }

    /// Clip `clip` of the input (training clips first, then validation): the tensor that
    /// holds it and its index there.
    pub fn clip(&self, clip: usize) -> (&Tensor, i64) {
        let n_train = self.n_train() as usize;
        if clip < n_train {
            (&self.train, clip as i64)
        } else {
            (&self.val, (clip - n_train) as i64)
        }
    }

    /// The start time since the release of clip `clip` \[1\], when known.
    pub fn clip_start(&self, clip: usize) -> Option<Tensor> {
        let n_train = self.n_train() as usize;
        let (times, i) = if clip < n_train {
            (&self.train_start, clip)
        } else {
            (&self.val_start, clip - n_train)
        };
        times.as_ref().map(|t| t.narrow(0, i as i64, 1))
    }
}

/// Subtracts the mean training frame and divides by the training pixels' overall standard
/// deviation (a fixed affine map of the input, computed on the training clips only): the static
/// background drops out and the encoder's first layer starts well conditioned.
/// Returns the map as (mean frame [D], std).
/// The sum of squares is accumulated over pieces of frames, so no full-size temporary is made
/// (a mostly static recording has a pixel variance far below the mean square, so the shortcut
/// mean(x²) − mean(m²) would cancel catastrophically in float32).
fn standardisation(all: &Tensor, n_train: i64) -> (Tensor, Tensor) {
    let d = all.size()[2];
    let train = all.narrow(0, 0, n_train).reshape([-1, d]);
    let mean = train.mean_dim(0, false, Kind::Float);
    let rows = train.size()[0];
    let mut sum_sq = 0.0f64;
    for s in (0..rows).step_by(512) {
        let piece = train.narrow(0, s, (rows - s).min(512)) - &mean;
        sum_sq += piece.square().sum(Kind::Double).double_value(&[]);
    }
    let std = (sum_sq / (rows * d) as f64).sqrt().max(1e-6);
    (mean, Tensor::from(std as f32).to_device(all.device()))
}

/// Frames, their shape and what is known about them, before they go to the device.
pub(crate) struct Source {
    /// The clips [N, T, C, H, W]; or, with `clip_index`, a recording's frames [F, C·H·W].
    pub(crate) frames: Vec<f32>,
    /// For a recording: the frame of every clip frame [N·T].
    pub(crate) clip_index: Option<Vec<i64>>,
    /// Of the clips.
    pub(crate) shape: [usize; 5],
    pub(crate) meta: Option<DatasetMeta>,
    pub(crate) start_times: Option<Vec<f64>>,
    pub(crate) recording: Option<RecordingSummary>,
    pub(crate) warnings: Vec<String>,
    pub(crate) preview_png: Option<Vec<u8>>,
}

/// Whether every sequence of `sequence` values (frames of `per_frame` values) holds one frame
/// repeated; `Some(Some(v))` when that frame is `v` everywhere as well.
fn still(frames: &[f32], sequence: usize, per_frame: usize) -> Option<Option<f32>> {
    let moves = frames.chunks(sequence.max(1)).any(|seq| {
        let (first, rest) = seq.split_at(per_frame.min(seq.len()));
        rest.chunks(per_frame.max(1))
            .any(|f| f.iter().zip(first).any(|(a, b)| a != b))
    });
    if moves {
        return None;
    }
    let v = frames.first().copied();
    Some(v.filter(|v| frames.iter().all(|x| x == v)))
}

/// Reads the input as its probe planned (`plan`) for `model`, and moves the frames to `device`.
pub fn load_clips(
    req: &LoadRequest,
    plan: &Plan,
    model: ModelRef,
    device: Device,
) -> Result<ClipData, EstimateError> {
    let src = match plan {
        Plan::Recording(p) => recording::recording_source(req, p, model)?,
        Plan::Dataset(header) => dataset::dataset_source(header, req.frames.as_deref())?,
    };
    let [n, t, c, h, w] = src.shape;
    // A recording's frames are one sequence; a dataset's, one per clip.
    let per_frame = c * h * w;
    let sequence = match src.clip_index {
        Some(_) => src.frames.len(),
        None => t * per_frame,
    };
    if let Some(v) = still(&src.frames, sequence, per_frame) {
        return Err(input_error(format!(
            "{}: nothing moves: within every {} each frame equals the first{}, so no parameter \
             of the motion can be estimated (check the file, or --crop for a recording)",
            req.input.display(),
            if src.clip_index.is_some() {
                "recording"
            } else {
                "clip"
            },
            v.map_or(String::new(), |v| format!(
                " (every pixel {})",
                num(v as f64)
            ))
        )));
    }
    let mut src = src;
    if let Err((i, v, spread)) = scale::rescale(&mut src.frames) {
        let per_frame = c * h * w;
        let (frame, pixel) = (i / per_frame, i % per_frame);
        let at = match src.clip_index {
            Some(_) => format!("frame {frame}"),
            None => format!("clip {}, frame {}", frame / t, frame % t),
        };
        return Err(input_error(format!(
            "{}: the value {} at {at}, pixel {pixel} lies more than {:e} times the frames' \
             spread ({}) from their median: a hot pixel or a broken value; mask or fix it",
            req.input.display(),
            num(v as f64),
            scale::OUTLIER,
            num(spread)
        )));
    }
    let photometric = photometric::normalise(&mut src.frames, (c, h, w));
    let truth: BTreeMap<String, f64> = src
        .meta
        .as_ref()
        .map(|m| m.model.parameters.clone())
        .unwrap_or_default();
    let d = (c * h * w) as i64;
    let source = Tensor::from_slice(&src.frames).to_device(device);
    drop(src.frames);
    // A recording's clips are gathered from its frames, which stay for the timeline.
    let (mut all, mut frames) = match &src.clip_index {
        Some(idx) => {
            let frames = source.view([-1, d]);
            let idx = Tensor::from_slice(idx).to_device(device);
            let clips = frames.index_select(0, &idx).view([n as i64, t as i64, d]);
            (clips, Some(frames))
        }
        None => (source.view([n as i64, t as i64, d]), None),
    };
    let n_val = ((n as f64 * 0.2).round() as i64).max(1);
    let n_train = n as i64 - n_val;
    let (mean, std) = standardisation(&all, n_train);
    // In place: no second copy of the clips.
    all -= &mean;
    all /= &std;
    if let Some(f) = frames.as_mut() {
        *f -= &mean;
        *f /= &std;
    }
    let start = src
        .start_times
        .as_ref()
        .map(|t| Tensor::from_slice(t).to_kind(Kind::Float).to_device(device));
    let recording = src
        .recording
        .zip(frames)
        .map(|(summary, f)| (summary, f.unsqueeze(0)));
    let background = &mean / &std;
    let rising = recording
        .as_ref()
        .and_then(|(s, _)| s.descent)
        .is_some_and(|d| d.rising);
    Ok(ClipData {
        rising,
        background,
        train: all.narrow(0, 0, n_train),
        val: all.narrow(0, n_train, n_val),
        train_start: start.as_ref().map(|t| t.narrow(0, 0, n_train)),
        val_start: start.as_ref().map(|t| t.narrow(0, n_train, n_val)),
        frames_per_clip: t as i64,
        inputs: d,
        shape: src.shape,
        truth,
        meta: src.meta,
        recording,
        warnings: src.warnings,
        preview_png: src.preview_png,
        photometric,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn standardisation_keeps_a_small_spread_over_a_bright_static_background() {
        // A mostly static recording: pixels near 0.7 that vary by 1e-3. A float32 shortcut
        // (mean of squares minus square of means) loses this spread entirely.
        let n = 50 * 20 * 64;
        let v: Vec<f32> = (0..n)
            .map(|i| 0.7 + 1e-3 * ((i * 7919 % 1000) as f32 / 500.0 - 1.0))
            .collect();
        let all = Tensor::from_slice(&v).view([50, 20, 64]);
        let (mean, std) = standardisation(&all, 40);
        assert!((mean.mean(Kind::Float).double_value(&[]) - 0.7).abs() < 1e-4);
        let expect = 1e-3 / 3f64.sqrt(); // a uniform spread over ±1e-3
        let got = std.double_value(&[]);
        assert!(
            (got / expect - 1.0).abs() < 0.05,
            "std {got}, expected {expect}"
        );
    }

    #[test]
    fn frames_that_never_change_are_still() {
        // Two clips of three 2-pixel frames.
        let flat = [0.5f32; 12];
        assert_eq!(still(&flat, 6, 2), Some(Some(0.5)));
        let mut each_its_own = flat;
        each_its_own[6..].fill(0.2);
        assert_eq!(still(&each_its_own, 6, 2), Some(None));
        let mut one_pixel_moves = each_its_own;
        one_pixel_moves[11] = 0.3;
        assert_eq!(still(&one_pixel_moves, 6, 2), None);
        assert_eq!(still(&[-0.0f32, 0.0, -0.0, 0.0], 4, 1), Some(Some(-0.0)));
    }
}
