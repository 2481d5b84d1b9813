//! The model chosen by the evidence (`--model auto`, or no `--model` on a recording or a bare
//! `.npy`): which candidates are tried (the built-in laws of one latent number, the laws of
//! bodies' positions where those are given, and `--candidate` files), each candidate's command
//! line, and each fit summarised for the ranking in `rank.rs`. The fits themselves are run by
//! `run`, which hands each one's report here.

pub mod cut;
pub mod rank;

use crate::cli::{EstimateArgs, ModelSpec};
use crate::error::{input_error, EstimateError};
use crate::physics::{ModelRef, MODELS};
use crate::report::Report;
use cut::CommonCut;
use physvid_shared::dataset::{read_meta, META_FILE};
use physvid_shared::meta::DatasetMeta;
use physvid_shared::video::is_recording;
use rank::Candidate;

/// Laws that differ only in what their answer is calibrated by: the frames cannot tell them
/// apart, the calibration decides (the first when `--incline-deg` or meta.json gives an
/// incline, the second otherwise).
const SAME_LAW: &[(&str, &str)] = &[("sliding-block", "free-fall")];

/// Whether this run chooses its model: `--model auto`, or no `--model` on an input that does
/// not name one (a recording or a bare `.npy`; a data set's meta.json names its model).
pub fn wanted(args: &EstimateArgs) -> Result<bool, EstimateError> {
    let wanted = match args.model.model {
        Some(ModelSpec::Auto) => true,
        Some(ModelSpec::Given(_)) => false,
        None => !is_data_set(args.input()),
    };
    if !wanted && !args.model.candidate.is_empty() {
        return Err(input_error(
            "--candidate: tried only when the model is chosen (--model auto, or no --model on a recording); drop it or pass --model auto",
        ));
    }
    Ok(wanted)
}

/// The candidates' command lines: the user's, with the model set, the flags a candidate does
/// not read dropped (a calibration it has no use for, `--init` of parameters it lacks), a
/// recording's clips cut alike for all (`cut`), one member and no progress bars; and the
/// common cut's reason.
pub fn candidates(
    args: &EstimateArgs,
) -> Result<(Vec<EstimateArgs>, Option<String>), EstimateError> {
    physvid_shared::input::check_kind(args.input()).map_err(input_error)?;
    let meta = meta_of(args);
    let calibration = meta.as_ref().map(|m| &m.calibration);
    let positions = !args.model.reference_positions().is_empty()
        || calibration.is_some_and(|c| !c.reference_positions.is_empty());
    let incline =
        args.model.incline_deg.is_some() || calibration.is_some_and(|c| c.incline_deg.is_some());
    let left_out = |m: &ModelRef| {
        SAME_LAW.iter().any(|&(needs_incline, otherwise)| {
            m.name() == if incline { otherwise } else { needs_incline }
        })
    };
    let models: Vec<ModelRef> = MODELS
        .iter()
        .map(|m| ModelRef(*m))
        .filter(|m| (m.latent_dims() > 1) == positions && !left_out(m))
        .chain(args.model.candidate.iter().copied())
        .collect();
    if models.is_empty() {
        return Err(input_error(
            "--model auto: no candidate reads bodies' positions but the built-in spring; pass --model",
        ));
    }
    let cut = cut::common_cut(args)?;
    let tries = models
        .into_iter()
        .map(|m| candidate_args(args, m, cut.as_ref()))
        .collect();
    Ok((tries, cut.map(|c| c.why)))
}

/// `args` for trying `model` (on the `cut` shared by all, unless it is released from rest).
fn candidate_args(args: &EstimateArgs, model: ModelRef, cut: Option<&CommonCut>) -> EstimateArgs {
    let mut a = args.clone();
    if let Some(c) = cut.filter(|_| !model.released_from_rest()) {
        a.recording.frames_per_clip = Some(c.frames_per_clip);
        a.recording.stride = Some(c.stride);
    }
    let m = &mut a.model;
    m.model = Some(ModelSpec::Given(model));
    m.candidate.clear();
    let reads = |flag: &str| model.info().calibration_flags.contains(&flag);
    if !reads("--reference") {
        m.reference = None;
    }
    if !reads("--incline-deg") {
        m.incline_deg = None;
    }
    if !reads("--g") {
        m.g = None;
    }
    if let Some(init) = m.init.as_mut() {
        init.0
            .retain(|(name, _)| model.parameters().iter().any(|p| p.name == name));
    }
    a.trying = true;
    a.training.ensemble = 1;
    a.output.quiet = true;
    a
}

/// Whether `input` is a data set directory (whose meta.json names its model), not a
/// recording (a video, an image folder) or a bare `.npy`.
fn is_data_set(input: &std::path::Path) -> bool {
    input.is_dir() && !is_recording(input)
}

/// A data set's meta.json, where the input is one (read for its calibration only; a broken one
/// is reported by each candidate's load).
fn meta_of(args: &EstimateArgs) -> Option<DatasetMeta> {
    let input = args.input();
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
            explains: false,
        },
    }
}
