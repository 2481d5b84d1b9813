//! `RunConfig`: the one resolved configuration of an `estimate` run (ripgrep's high-level
//! arguments), made from a typed `Request` (`request.rs`: the command line's flags, or a
//! program's) and a probe of the input before any frame is read:
//! model, dt, the load's plan, every per-model default, the calibration. What only frames tell
//! is settled once they are loaded (`frames`). Nothing downstream re-derives a default.

mod checks;
mod frames;
pub mod request;

pub use request::{CalibrationRequest, Request, TrainingRequest};

use checks::{check_calibration_flags, check_dt, check_references};

use crate::calibration::Calibration;
use crate::data::{LoadRequest, Plan, Probe};
use crate::device::DeviceChoice;
use crate::encoder::EncoderKind;
use crate::error::{input_error, EstimateError};
use crate::loss::LossKind;
use crate::physics::{Integrator, ModelRef, RolloutStart};
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
    /// The request named the encoder (what the frames show does not change it).
    #[serde(skip)]
    pub encoder_named: bool,
    pub seed: u64,
    /// Independently seeded trainings whose spread is reported (1: a single run).
    pub ensemble: usize,
    pub device: DeviceChoice,
    /// CPU threads for libtorch.
    pub threads: usize,
    pub out: PathBuf,
    /// `--force`: write into a folder this tool did not make.
    #[serde(skip)]
    pub force: bool,
    pub quiet: bool,
    /// What to load (the input and the recording flags) and how (the probe's plan): the load
    /// reads these and the model, nothing else.
    #[serde(skip)]
    pub request: LoadRequest,
    #[serde(skip)]
    pub plan: Plan,
    /// `--reference` times of a recording, placed on its clip frames once it is cut.
    #[serde(skip)]
    pub reference_times: Vec<(f64, f64)>,
    /// What was said of those taken at an end of the part kept (`with_frames`; warnings).
    pub reference_notes: Vec<String>,
}

impl RunConfig {
    /// Resolves `req` against the probe of its input.
    pub fn resolve(req: &Request, probe: Probe) -> Result<RunConfig, EstimateError> {
        let Probe { model, dt, plan } = probe;
        let (c, t) = (&req.calibration, &req.training);
        let init = initial_values(model, &req.init)?;
        if t.loss == LossKind::ResidualFloor && !model.supports_residual() {
            return Err(input_error(format!(
                "--loss residual+floor: implemented for damped-oscillator only, not {}; use --loss mse+kl",
                model.name()
            )));
        }
        if req.integrator == Integrator::Euler && !model.info().training.has_euler {
            return Err(input_error(format!(
                "--integrator euler: {} has no Euler step (it is integrated by RK4); use --integrator exact",
                model.name()
            )));
        }
        let model_note = model.info().training.encoder_note.map(String::from);
        let (encoder, encoder_note) = match t.encoder {
            Some(e) => (e, None),
            None => (model.encoder(), model_note),
        };
        if !encoder.gives(model.latent_dims()) {
            return Err(input_error(format!(
                "--encoder {}: reads body positions, and {} has a latent of {} number(s) per frame; use --encoder small",
                encoder.name(),
                model.name(),
                model.latent_dims()
            )));
        }
        check_dt(model, dt, &plan)?;
        check_calibration_flags(model, c)?;
        let reference_times = c.times.clone();
        if let (Some(&(t, v)), Plan::Dataset(_)) = (reference_times.first(), &plan) {
            return Err(input_error(format!(
                "--reference {}s={}: times apply to recordings; for a data set give CLIP:FRAME=VALUE",
                num(t),
                num(v)
            )));
        }
        let calibration = Calibration::resolve(
            &c.values,
            &c.positions,
            !reference_times.is_empty(),
            c.incline_deg,
            c.g,
            plan.meta().map(|meta| &meta.calibration),
        );
        // The values are checked once the times are placed on frames, with the others.
        check_references(&calibration, model, reference_times.is_empty())?;
        Ok(RunConfig {
            input: req.input().to_path_buf(),
            model,
            dt,
            epochs: t.epochs,
            patience: t.patience.unwrap_or(model.patience()),
            batch_size: t.batch_size,
            lr: t.lr,
            lr_phys: t.lr_phys,
            init,
            calibration,
            integrator: req.integrator,
            rollout_start: req.rollout_start,
            single_start: t.single_start,
            loss: t.loss,
            encoder,
            encoder_note,
            encoder_named: t.encoder.is_some(),
            seed: t.seed,
            ensemble: t.ensemble,
            device: t.device,
            threads: t.threads,
            out: req.out.clone(),
            force: req.force,
            quiet: req.quiet,
            request: req.load.clone(),
            plan,
            reference_times,
            reference_notes: Vec::new(),
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

    /// A probe as `data::probe` makes it for a 30-fps video cut at stride 3 (no file read).
    fn recording(model: &str) -> Probe {
        Probe {
            model: ModelRef::by_name(model).unwrap(),
            dt: 0.1,
            plan: Plan::Recording(crate::data::RecordingPlan {
                info: None,
                fps: 30.0,
                fps_source: "--fps",
                frames_per_clip: 20,
                stride: 3,
                warnings: Vec::new(),
            }),
        }
    }

    fn args(flags: &[&str]) -> Request {
        use clap::Parser;
        let line = ["estimate", "clip.mp4"].iter().chain(flags);
        crate::cli::EstimateArgs::try_parse_from(line)
            .unwrap()
            .request()
            .unwrap()
    }

    #[test]
    fn the_configuration_is_resolved_from_the_probe_before_any_frame() {
        let a = args(&["--model", "torricelli", "--reference", "3s=0.07,12s=0.04"]);
        let cfg = RunConfig::resolve(&a, recording("torricelli")).unwrap();
        assert_eq!((cfg.model.name(), cfg.dt), ("torricelli", 0.1));
        assert_eq!(cfg.request, a.load);
        // The times wait for the cut to be placed on frames; they are the flags' already.
        assert_eq!(cfg.reference_times, vec![(3.0, 0.07), (12.0, 0.04)]);
        assert!(cfg.calibration.reference.is_empty());
        assert_eq!(cfg.calibration.source, "flags");
    }

    #[test]
    fn flags_the_probe_refutes_are_refused_without_frames() {
        let refused = |flags: &[&str], probe: Probe| {
            RunConfig::resolve(&args(flags), probe)
                .unwrap_err()
                .to_string()
        };
        let e = refused(&["--init", "gamma7=1"], recording("pendulum"));
        assert!(e.contains("no parameter 'gamma7'"), "{e}");
        let e = refused(&["--loss", "residual+floor"], recording("pendulum"));
        assert!(e.contains("damped-oscillator only"), "{e}");
        let e = refused(&["--reference", "3s=0.07,12s=0.04"], {
            let mut p = recording("torricelli");
            p.plan = Plan::Dataset(Box::new(physvid_shared::DatasetHeader {
                shape: [2, 20, 1, 32, 32],
                meta: None,
                frames_path: "clips.npy".into(),
            }));
            p
        });
        assert!(e.contains("times apply to recordings"), "{e}");
        let e = refused(&[], {
            let mut p = recording("pendulum");
            p.dt = 1e9;
            p
        });
        assert!(e.contains("dt = --stride / fps"), "{e}");
    }
}
