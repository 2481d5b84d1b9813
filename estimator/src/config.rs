//! `RunConfig`: the one resolved configuration of an `estimate` run (ripgrep's high-level
//! arguments), made once from the command line and the loaded clips: the model and dt (flags
//! or meta.json), every per-model default (encoder, patience, starts), the calibration, and
//! the checks that need the data. Nothing downstream re-derives a default.

use crate::calibration::Calibration;
use crate::cli::{calibration_flag, EstimateArgs, ModelArgs};
use crate::data::{ClipData, Settled};
use crate::device::DeviceChoice;
use crate::encoder::EncoderKind;
use crate::error::{input_error, EstimateError};
use crate::loss::LossKind;
use crate::physics::info::DT_RANGE;
use crate::physics::{Integrator, ModelRef, RolloutStart, MODELS};
use physvid_shared::cli::num;
use serde::Serialize;
use std::path::PathBuf;

/// Settings of one run, every default filled in.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunConfig {
    pub input: PathBuf,
    pub model: ModelRef,
    /// Seconds between the frames of a clip.
    pub dt: f64,
    /// Upper bound on epochs; the early stop usually ends the run sooner.
    pub epochs: usize,
    /// Epochs without a better validation metric before stopping.
    pub patience: usize,
    pub batch_size: usize,
    /// Adam learning rate of the encoder.
    pub lr: f64,
    /// Adam learning rate of the physics parameters.
    pub lr_phys: f64,
    /// Starting values of the block's parameters, in the model's order.
    pub init: Vec<f64>,
    /// Reported at the top of report.json, not again here.
    #[serde(skip)]
    pub calibration: Calibration,
    pub integrator: Integrator,
    /// Where the oscillator's rollout starts.
    pub rollout_start: RolloutStart,
    /// Train only from `init`, without starts read off the data.
    pub single_start: bool,
    pub loss: LossKind,
    pub encoder: EncoderKind,
    /// Why the model chose `encoder` itself, when it did and no flag chose (a warning).
    pub encoder_note: Option<String>,
    pub seed: u64,
    /// Independently seeded trainings whose spread is reported (1: a single run).
    pub ensemble: usize,
    pub device: DeviceChoice,
    /// CPU threads for libtorch.
    pub threads: usize,
    pub out: PathBuf,
    pub quiet: bool,
}

impl RunConfig {
    /// Resolves `args` (validated) against the loaded clips and what their loading settled.
    pub fn resolve(
        args: &EstimateArgs,
        data: &ClipData,
        settled: Settled,
    ) -> Result<RunConfig, EstimateError> {
        let Settled { model, dt } = settled;
        let (m, t) = (&args.model, &args.training);
        let init = initial_values(model, m.init_pairs())?;
        if t.loss == LossKind::ResidualFloor && !model.supports_residual() {
            return Err(input_error(format!(
                "--loss residual+floor: implemented for damped-oscillator only, not {}; use --loss mse+kl",
                model.name()
            )));
        }
        if m.integrator == Integrator::Euler && !model.info().training.has_euler {
            return Err(input_error(format!(
                "--integrator euler: {} has no Euler step (it is integrated by RK4); use --integrator exact",
                model.name()
            )));
        }
        let (encoder, encoder_note) = default_encoder(t.encoder, model, data);
        if !encoder.gives(model.latent_dims()) {
            return Err(input_error(format!(
                "--encoder {}: reads body positions, and {} has a latent of {} number(s) per frame; use --encoder small",
                encoder.name(),
                model.name(),
                model.latent_dims()
            )));
        }
        check_dt(model, dt, data)?;
        check_calibration_flags(model, m)?;
        let [n, frames, _, height, width] = data.shape;
        let (min_side, why) = model.info().footage.min_frame;
        if height.min(width) < min_side {
            return Err(input_error(format!(
                "{}: frames of {width}×{height} px are too small for {} ({why}); need at least {min_side}×{min_side}",
                args.input().display(),
                model.name()
            )));
        }
        let mut reference = m.reference_points().to_vec();
        if let Some(&(t, v)) = m.reference_times().first() {
            let Some((rec, _)) = &data.recording else {
                return Err(input_error(format!(
                    "--reference {}s={}: times apply to recordings; for a data set give CLIP:FRAME=VALUE",
                    num(t),
                    num(v)
                )));
            };
            let frames = rec
                .reference_frames(m.reference_times())
                .map_err(|e| input_error(format!("--reference {e}")))?;
            reference.extend(frames);
        }
        let calibration = Calibration::resolve(
            &reference,
            m.reference_positions(),
            m.incline_deg,
            m.g,
            data.meta.as_ref().map(|meta| &meta.calibration),
        );
        calibration
            .check_positions(model.latent_dims())
            .map_err(input_error)?;
        if model.latent_dims() > 1 && !calibration.reference.is_empty() {
            return Err(input_error(format!(
                "{}: {} needs the bodies' positions at reference frames, CLIP:FRAME=X1/Y1/X2/Y2 (pixels), not one value",
                calibration.origin(),
                model.name()
            )));
        }
        if model.latent_dims() == 1 && !calibration.positions.is_empty() {
            return Err(input_error(format!(
                "{}: {} takes one value per reference frame, CLIP:FRAME=VALUE, not body positions",
                calibration.origin(),
                model.name()
            )));
        }
        calibration
            .check_values(model.info().calibration.nonnegative_reference)
            .map_err(input_error)?;
        if let Some((c, f, p)) = calibration.positions.iter().find(|(_, _, p)| {
            p.chunks(2).any(|xy| {
                !(0.0..=width as f64).contains(&xy[0]) || !(0.0..=height as f64).contains(&xy[1])
            })
        }) {
            return Err(input_error(format!(
                "{} {c}:{f}: {p:?} lies outside the {width}×{height} frame (positions are pixels, x right, y down)",
                calibration.origin()
            )));
        }
        let frames_at = calibration
            .reference
            .iter()
            .map(|&(c, f, _)| (c, f))
            .chain(calibration.positions.iter().map(|(c, f, _)| (*c, *f)));
        if let Some((c, f)) = frames_at.into_iter().find(|&(c, f)| c >= n || f >= frames) {
            return Err(input_error(format!(
                "{} {c}:{f}: the data has clips 0..{n} and frames 0..{frames}",
                calibration.origin()
            )));
        }
        Ok(RunConfig {
            input: args.input().to_path_buf(),
            model,
            dt,
            epochs: t.epochs,
            patience: t.patience.unwrap_or(model.patience()),
            batch_size: t.batch_size,
            lr: t.lr,
            lr_phys: t.lr_phys,
            init,
            calibration,
            integrator: m.integrator,
            rollout_start: m.rollout_start,
            single_start: t.single_start,
            loss: t.loss,
            encoder,
            encoder_note,
            seed: t.seed,
            ensemble: t.ensemble,
            device: t.device,
            threads: t.thread_count(),
            out: args.output.out.clone(),
            quiet: args.output.quiet,
        })
    }

    /// This configuration for ensemble member `seed`.
    pub fn with_seed(&self, seed: u64) -> RunConfig {
        RunConfig {
            seed,
            ..self.clone()
        }
    }
}

/// The encoder: `--encoder`, else the model's, except that on a recording of an object
/// released from rest across the frame (a descent found), or of one object moving about it
/// where the built-in model's is the small MLP (`data::object`), it is read by its position
/// (the centroid encoder); and why, when the choice was made here or by the model.
fn default_encoder(
    flag: Option<EncoderKind>,
    model: ModelRef,
    data: &ClipData,
) -> (EncoderKind, Option<String>) {
    if let Some(e) = flag {
        return (e, None);
    }
    let descent = data.recording.as_ref().and_then(|(r, _)| r.descent);
    if let (Some(d), 1) = (descent, model.latent_dims()) {
        return (
            EncoderKind::Centroid,
            Some(format!(
                "the object released from rest crosses {:.0} % of the frame: it is read by its \
                 position (--encoder centroid: the validation clips, the recording's end, show \
                 it where no training clip did, and an MLP has no weights there); --encoder \
                 chooses",
                100.0 * d.travel
            )),
        );
    }
    // Built-in models only: a model file's pendulum read this way lost its g/L on the shared
    // pendulum (+14 %, the built-in +0.5 %), not yet understood.
    let object = data.recording.as_ref().and_then(|(r, _)| r.object);
    let built_in = model.info().law.file.is_none();
    if let (Some(o), 1, EncoderKind::Small, true) =
        (object, model.latent_dims(), model.encoder(), built_in)
    {
        return (
            EncoderKind::Centroid,
            Some(format!(
                "an object moves about {:.0} % of the frame: it is read by its position \
                 (--encoder centroid: an MLP on pixels compresses large swings more than small \
                 ones, which lowers a damping); --encoder chooses",
                100.0 * o.travel
            )),
        );
    }
    (
        model.encoder(),
        model.info().training.encoder_note.map(String::from),
    )
}

/// Starting values for `model`, in its parameter order: its defaults, overridden by `--init`;
/// unknown names and non-positive starts of positive parameters are errors.
pub fn initial_values(model: ModelRef, init: &[(String, f64)]) -> Result<Vec<f64>, EstimateError> {
    let specs = model.parameters();
    let mut values = model.default_init();
    for (name, v) in init {
        let i = specs.iter().position(|p| p.name == name).ok_or_else(|| {
            input_error(format!(
                "--init {name}={v}: {} has no parameter '{name}'; its parameters are {}",
                model.name(),
                model.parameter_names().join(", ")
            ))
        })?;
        let b = specs[i].bounds;
        if b.is_positive() && *v <= 0.0 {
            return Err(input_error(format!("--init {name}={v}: must be > 0")));
        }
        if !b.contains(*v) {
            return Err(input_error(format!(
                "--init {name}={v}: must lie strictly inside its bounds ({}, {})",
                num(b.lo),
                num(b.hi)
            )));
        }
        values[i] = *v;
    }
    Ok(values)
}

/// Refuses a calibration flag the model's answers do not read, naming the models that do.
fn check_calibration_flags(model: ModelRef, m: &ModelArgs) -> Result<(), EstimateError> {
    let Some(c) = m
        .calibration_given()
        .into_iter()
        .find(|c| !model.info().calibration.inputs.contains(c))
    else {
        return Ok(());
    };
    let readers: Vec<&str> = MODELS
        .iter()
        .filter(|r| r.info().calibration.inputs.contains(&c))
        .map(|r| r.name())
        .collect();
    Err(input_error(format!(
        "{}: {} does not use it (its answers need no calibration of that kind); it applies \
         to {}; drop it",
        calibration_flag(c),
        model.name(),
        readers.join(", ")
    )))
}

/// The data's `dt` against [`DT_RANGE`] and the model's longest, naming where it came from.
fn check_dt(model: ModelRef, dt: f64, data: &ClipData) -> Result<(), EstimateError> {
    let source = if data.recording.is_some() {
        "dt = --stride / fps"
    } else if data.meta.is_some() {
        "meta.json's dt"
    } else {
        "--dt"
    };
    let (lo, hi) = DT_RANGE;
    if !(lo..=hi).contains(&dt) {
        return Err(input_error(format!(
            "{source} {} s: outside {lo:e}–{hi} s (a million frames per second to one a day); give dt in seconds",
            num(dt)
        )));
    }
    let (max, why) = model.info().footage.max_dt;
    if dt > max {
        return Err(input_error(format!(
            "{source} {} s: {} takes dt ≤ {max} s ({why})",
            num(dt),
            model.name()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn init_overrides_defaults_by_name_and_checks_them() {
        let m = ModelRef::by_name("damped-oscillator").unwrap();
        assert_eq!(initial_values(m, &[]).unwrap(), vec![1.0, 0.1]);
        let v = initial_values(m, &[("gamma1".into(), 0.5)]).unwrap();
        assert_eq!(v, vec![1.0, 0.5]);
        let e = initial_values(m, &[("gamma7".into(), 1.0)]).unwrap_err();
        assert!(e.to_string().contains("gamma7"), "{e}");
        let e = initial_values(m, &[("gamma0".into(), -1.0)]).unwrap_err();
        assert!(e.to_string().contains("must be > 0"), "{e}");
    }
}
