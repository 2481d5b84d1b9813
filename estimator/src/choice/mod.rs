//! The model chosen by the evidence (`--model auto`, or no `--model` on a recording or a bare
//! `.npy`): which candidates are tried (the built-in laws of one latent number, the laws of
//! bodies' positions where those are given, and `--candidate` files), the cut of a recording
//! they share, and each fit summarised for the ranking in `rank.rs`. Each candidate's command
//! line is the CLI's (`cli::candidate`); the fits are run by `run`, which hands each one's
//! report here.

pub mod candidate;
pub mod cut;
pub mod rank;

use crate::data::RecordingRequest;
use crate::error::{input_error, EstimateError};
use crate::physics::{ModelRef, MODELS};
use crate::report::Report;
use cut::CommonCut;
use physvid_shared::dataset::{read_meta, META_FILE};
use physvid_shared::meta::DatasetMeta;
use physvid_shared::video::is_recording;
use rank::Candidate;
use std::path::{Path, PathBuf};

/// Laws that differ only in what their answer is calibrated by: the frames cannot tell them
/// apart, the calibration decides (the first when `--incline-deg` or meta.json gives an
/// incline, the second otherwise).
const SAME_LAW: &[(&str, &str)] = &[("sliding-block", "free-fall")];

/// What a model choice reads of the command line (resolved there:
/// `cli::EstimateArgs::choice_request`).
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
    physvid_shared::input::check_kind(&req.input).map_err(input_error)?;
    let meta = meta_of(&req.input);
    let calibration = meta.as_ref().map(|m| &m.calibration);
    let positions = req.positions || calibration.is_some_and(|c| !c.reference_positions.is_empty());
    let incline = req.incline || calibration.is_some_and(|c| c.incline_deg.is_some());
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
    Ok((models, cut::common_cut(&req.input, &req.recording)?))
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

/// `model`'s fit as the ranking sees it: its report, or why it gave none.
pub fn summary(model: ModelRef, fit: Result<&Report, String>) -> Candidate {
    let parameters = model.parameters().len();
    match fit {
        Ok(r) => Candidate {
            model: model.name().to_string(),
            grade: Some(r.verdict.grade),
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
                .map(|p| format!("{} = {} {}", p.name, crate::html::sig(p.estimate), p.unit))
                .collect::<Vec<_>>()
                .join(", "),
            reasons: r
                .verdict
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
