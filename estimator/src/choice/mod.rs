//! The model chosen by the evidence (`--model auto`, or no `--model` on a recording or a bare
//! `.npy`): which candidates are tried (the built-in laws of one latent number, the laws of
//! bodies' positions where those are given, and `--candidate` files), the cut of a recording
//! they share, each candidate's request derived from the user's (`candidate_request`), and
//! each fit summarised for the ranking in `rank.rs`. The fits are run by `run`, which hands
//! each one's result here.

pub mod candidate;
pub mod close;
pub mod cut;
pub mod rank;

use crate::analysis::Run;
use crate::calibration::CalibrationInput;
use crate::config::Request;
use crate::data::RecordingRequest;
use crate::digits::sig;
use crate::error::{input_error, EstimateError};
use crate::physics::{ModelRef, MODELS};
use crate::verdict::Verdict;
use cut::CommonCut;
use physvid_shared::dataset::{read_meta, META_FILE};
use physvid_shared::meta::DatasetMeta;
use physvid_shared::video::is_recording;
use rank::Candidate;
use std::path::{Path, PathBuf};

/// Laws that differ only in what their answer is calibrated by: the frames cannot tell them
/// apart, the calibration or the track decides (the first when `--incline-deg` or meta.json
/// gives an incline, or the track's constant acceleration lies off the picture's vertical,
/// `data::falls`: a slide, a roll or a cart; the second otherwise).
const SAME_LAW: &[(&str, &str)] = &[("sliding-block", "free-fall")];

/// What a model choice reads of the request (`ChoiceRequest::of`).
#[derive(Debug, Clone)]
pub struct ChoiceRequest {
    /// The recording, data set or array.
    pub input: PathBuf,
    pub recording: RecordingRequest,
    /// References give bodies' positions (the spring's calibration).
    pub positions: bool,
    /// An incline's angle is given (`--incline-deg`).
    pub incline: bool,
    /// The model files named as candidates (`--candidate`).
    pub files: Vec<ModelRef>,
    /// The clips are in memory (`LoadRequest::frames`): `input` only names them.
    pub in_memory: bool,
    /// Their meta.json, where they are a data set's.
    pub memory_meta: Option<DatasetMeta>,
}

/// `req` for trying `model` in a choice (on the `cut` shared by all, unless it is
/// released from rest): the model set, what it does not read dropped (a calibration it has
/// no use for, starting values of parameters it lacks), one member and no progress lines.
pub fn candidate_request(req: &Request, model: ModelRef, cut: Option<&CommonCut>) -> Request {
    let mut r = req.clone();
    if let Some(c) = cut.filter(|_| !model.released_from_rest()) {
        r.load.recording.frames_per_clip = Some(c.frames_per_clip);
        r.load.recording.stride = Some(c.stride);
    }
    r.load.model = Some(model);
    r.load.trying = true;
    r.choose = false;
    r.candidates.clear();
    for c in CalibrationInput::ALL {
        if !model.info().calibration.inputs.contains(&c) {
            r.calibration.drop(c);
        }
    }
    r.load.recording.measured_at = r.calibration.times.iter().map(|t| t.0).collect();
    r.init
        .retain(|(name, _)| model.parameters().iter().any(|p| p.name == name));
    r.training.ensemble = 1;
    r.quiet = true;
    r
}

impl ChoiceRequest {
    /// What the choice reads of `req`.
    pub fn of(req: &Request) -> ChoiceRequest {
        ChoiceRequest {
            input: req.input().to_path_buf(),
            recording: req.load.recording.clone(),
            positions: !req.calibration.positions.is_empty(),
            incline: req.calibration.incline_deg.is_some(),
            files: req.candidates.clone(),
            in_memory: req.load.frames.is_some(),
            memory_meta: req.load.frames.as_ref().and_then(|f| f.meta.clone()),
        }
    }
}

/// Whether a run without `--model` chooses its model: a recording or a bare `.npy` does, a
/// data set (whose meta.json names its model) does not.
pub fn chosen_without_model(input: &Path) -> bool {
    !is_data_set(input)
}

/// The candidates for `req`'s input (the built-in laws of one latent number, or of bodies'
/// positions where references give those, then the files), and the cut of a recording into
/// clips they all share (`cut`).
pub fn candidates(
    req: &ChoiceRequest,
) -> Result<(Vec<ModelRef>, Option<CommonCut>), EstimateError> {
    // Clips in memory are an array's or a data set's: their meta.json, if any, no recording
    // to cut.
    let meta = match req.in_memory {
        true => req.memory_meta.clone(),
        false => {
            physvid_shared::input::check_kind(&req.input).map_err(input_error)?;
            meta_of(&req.input)
        }
    };
    let calibration = meta.as_ref().map(|m| &m.calibration);
    let positions = req.positions || calibration.is_some_and(|c| !c.reference_positions.is_empty());
    let incline = req.incline
        || calibration.is_some_and(|c| c.incline_deg.is_some())
        || req.recording.tracked.is_some_and(|t| !t.falls());
    let left_out = |m: &ModelRef| {
        SAME_LAW.iter().any(|&(needs_incline, otherwise)| {
            m.name() == if incline { otherwise } else { needs_incline }
        })
    };
    let models: Vec<ModelRef> = MODELS
        .iter()
        .map(|m| ModelRef(*m))
        .filter(|m| (m.latent_dims() > 1) == positions && !left_out(m))
        .chain(req.files.iter().copied())
        .collect();
    if models.is_empty() {
        return Err(input_error(
            "--model auto: no candidate reads bodies' positions but the built-in spring; pass --model",
        ));
    }
    let cut = match req.in_memory {
        true => None,
        false => cut::common_cut(&req.input, &req.recording)?,
    };
    Ok((models, cut))
}

/// Whether `load`'s input names no model: a recording, a bare `.npy` or an array in memory do
/// not; a data set, in its folder or in memory, names its model in its meta.json.
pub fn names_no_model(load: &crate::data::LoadRequest) -> bool {
    match &load.frames {
        Some(f) => f.meta.is_none(),
        None => chosen_without_model(&load.input),
    }
}

/// Whether `input` is a data set directory (whose meta.json names its model), not a
/// recording (a video, an image folder) or a bare `.npy`.
fn is_data_set(input: &Path) -> bool {
    input.is_dir() && !is_recording(input)
}

/// A data set's meta.json, where the input is one (read for its calibration only; a broken one
/// is reported by each candidate's load).
fn meta_of(input: &Path) -> Option<DatasetMeta> {
    is_data_set(input)
        .then(|| read_meta(&input.join(META_FILE)).ok())
        .flatten()
}

/// `model`'s fit as the ranking sees it: its run and verdict, or why it gave none.
pub fn summary(model: ModelRef, fit: Result<(&Run, &Verdict), String>) -> Candidate {
    let parameters = model.parameters().len();
    match fit {
        Ok((r, verdict)) => Candidate {
            model: model.name().to_string(),
            grade: Some(verdict.grade),
            unexplained: r.evidence.law.as_ref().map(|l| l.unexplained_within),
            parameters,
            // Without a law fit, as a second-order rollout would.
            clip_states: r
                .evidence
                .law
                .as_ref()
                .map_or(2, |l| l.start_frames as usize),
            answer: r
                .parameters
                .iter()
                .filter(|p| p.units == "SI")
                .map(|p| format!("{} = {} {}", p.name, sig(p.estimate), p.unit))
                .collect::<Vec<_>>()
                .join(", "),
            reasons: verdict
                .reasons
                .iter()
                .map(|r| r.check.to_string())
                .collect(),
            picture: r.evidence.fold.as_ref().map(|f| f.explained_share),
            explains: false,
        },
        Err(why) => Candidate {
            model: model.name().to_string(),
            grade: None,
            unexplained: None,
            parameters,
            clip_states: 0,
            answer: why,
            reasons: Vec::new(),
            picture: None,
            explains: false,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::CalibrationRequest;

    #[test]
    fn a_candidate_is_asked_only_what_it_reads() {
        let mut req = Request::new("clip.mp4");
        req.choose = true;
        req.calibration.times = vec![(1.0, 0.5), (2.0, 0.2)];
        req.load.recording.measured_at = vec![1.0, 2.0];
        req.calibration.incline_deg = Some(10.0);
        req.init = vec![("gamma0".into(), 3.0), ("rate".into(), 0.1)];
        req.training.ensemble = 4;
        let oscillator = ModelRef::by_name("damped-oscillator").unwrap();
        let cut = CommonCut {
            frames_per_clip: 24,
            stride: 3,
            why: String::new(),
        };
        let r = candidate_request(&req, oscillator, Some(&cut));
        assert_eq!(r.load.model, Some(oscillator));
        assert!(r.load.trying && !r.choose && r.quiet);
        assert_eq!(r.training.ensemble, 1);
        assert_eq!(r.init, vec![("gamma0".to_string(), 3.0)]);
        // The oscillator's answers are SI without a calibration: none is asked of it.
        assert_eq!(r.calibration, CalibrationRequest::default());
        assert!(r.load.recording.measured_at.is_empty());
        assert_eq!(
            (r.load.recording.frames_per_clip, r.load.recording.stride),
            (Some(24), Some(3))
        );
        // A fall reads the reference (its distances), not an incline.
        let fall = ModelRef::by_name("free-fall").unwrap();
        let f = candidate_request(&req, fall, Some(&cut));
        assert_eq!(f.calibration.times, req.calibration.times);
        assert_eq!(f.load.recording.measured_at, vec![1.0, 2.0]);
        assert_eq!(f.calibration.incline_deg, None);
        assert_eq!(
            (f.load.recording.frames_per_clip, f.load.recording.stride),
            (None, None),
            "a fall from rest is cut its own way"
        );
    }

    #[test]
    fn a_tracked_acceleration_off_the_vertical_is_tried_as_a_slide() {
        let names = |axis: Option<[f64; 2]>| {
            let recording = RecordingRequest {
                tracked: axis.map(|axis| crate::data::TrackedMotion {
                    span: (0.0, 1.0),
                    release: Some(0.0),
                    axis,
                    travel: 0.5,
                    moving_before: false,
                    frame: None,
                }),
                ..RecordingRequest::default()
            };
            let req = ChoiceRequest {
                input: PathBuf::from("clips.npy"),
                recording,
                positions: false,
                incline: false,
                files: Vec::new(),
                in_memory: true,
                memory_meta: None,
            };
            let (models, _) = candidates(&req).unwrap();
            models.iter().map(|m| m.name()).collect::<Vec<_>>()
        };
        for (axis, tried, not) in [
            (None, "free-fall", "sliding-block"),
            (Some([0.02, 1.0]), "free-fall", "sliding-block"),
            // A cart pulled along a level track, either way; a roll down a 20° ramp.
            (Some([1.0, 0.0]), "sliding-block", "free-fall"),
            (Some([-1.0, -1e-4]), "sliding-block", "free-fall"),
            (Some([0.94, 0.34]), "sliding-block", "free-fall"),
        ] {
            let got = names(axis);
            assert!(
                got.contains(&tried) && !got.contains(&not),
                "{axis:?}: {got:?}"
            );
        }
    }
}
