//! Torricelli's tank h' = −k·√h (Delfys75): the model and its exact first-order block.

use super::block::{frame_index, BlockOptions, Clips, Integrator, PhysicsBlock};
use super::info::{Calibrates, Footage, ModelInfo, ParamSpec, Picture, Training, TruthKey};
use super::model::{Derived, Model};
use crate::calibration::{needs_reference, Calibration, CalibrationInput, DerivedValue, Readings};
use crate::encoder::EncoderKind;
use physvid_shared::systems;
use tch::nn;
use tch::{Kind, Tensor};

/// The draining tank of Delfys75.
pub struct Torricelli;

/// The water's area is affine in the pixels, and any √u = p + q·√h drains by the same law,
/// which an MLP could learn: a linear encoder pins the latent.
const INFO: ModelInfo = {
    let info = ModelInfo::of(
        &systems::TORRICELLI,
        "h' = −k·√h (k_latent, base)",
        &[
            ParamSpec::new("k_latent", 0.1, true),
            ParamSpec::offset("base", -3.0),
        ],
        &[TruthKey::positive("k")],
    );
    ModelInfo {
        footage: Footage {
            picture: Some(Picture::MovingEdge("the water line moves down the tank")),
            ..info.footage
        },
        training: Training {
            encoder: EncoderKind::Linear,
            ..Training::DEFAULT
        },
        calibration: Calibrates {
            nonnegative_reference: Some("a water level (m above the tank's bottom)"),
            ..Calibrates::by(&[CalibrationInput::Reference])
        },
        ..info
    }
};

impl Model for Torricelli {
    fn info(&self) -> &ModelInfo {
        &INFO
    }
    fn build(&self, path: &nn::Path, init: &[f64], opts: BlockOptions) -> Box<dyn PhysicsBlock> {
        Box::new(TorricelliBlock::new(path, init, opts.integrator, opts.dt))
    }
    /// k in SI takes the slope of √u against √h over the reference frames.
    fn derive(&self, params: &[f64], cal: &Calibration, readings: &Readings) -> Derived {
        let mut values = vec![
            DerivedValue::latent("k_latent", params[0]),
            DerivedValue::latent("base", params[1]),
        ];
        let mut warnings = Vec::new();
        match cal.root_scale(&readings.values, params[1]) {
            Some(q) => values.insert(
                0,
                DerivedValue::si("k", "m^0.5/s", params[0] / q.abs(), Some("k")),
            ),
            None => warnings.push(needs_reference("Torricelli's k")),
        }
        (values, warnings)
    }
}

/// With u = σ·(z − base) (σ = ±1 read off the data: the level falls) the block is
/// u' = −k_lat·√u, solved exactly as √u(t) = √u(0) − k_lat·t/2 (Euler: the paper's step). Any
/// latent with √u = p + q·√h obeys it, with k_lat = q·k; the SI k takes q from the reference
/// frames (see [`Calibration::root_scale`]). Parameters: k_latent (√latent/s), base (the latent
/// of an empty tank).
pub struct TorricelliBlock {
    log_k: Tensor,
    base: Tensor,
    integrator: Integrator,
    dt: f64,
}

impl TorricelliBlock {
    pub fn new(path: &nn::Path, init: &[f64], integrator: Integrator, dt: f64) -> Self {
        TorricelliBlock {
            log_k: path.var("log_k", &[], nn::Init::Const(init[0].ln())),
            base: path.var("base", &[], nn::Init::Const(init[1])),
            integrator,
            dt,
        }
    }
}

impl PhysicsBlock for TorricelliBlock {
    fn order(&self) -> i64 {
        1
    }
    fn rollout(&self, z: &Tensor, _clips: Clips, steps: i64) -> Tensor {
        // σ: the level falls, so u = σ(z − base) must fall over each clip (on the device).
        let trend = (z.select(1, steps - 1) - z.select(1, 0)).mean(Kind::Float);
        let sigma = trend.le(0.0).to_kind(Kind::Float) * 2.0 - 1.0;
        let k = self.log_k.exp();
        let u0 = ((z.narrow(1, 0, 1) - &self.base) * &sigma).clamp_min(0.0);
        let u = match self.integrator {
            Integrator::Exact => {
                let t = frame_index(steps, z) * self.dt;
                ((u0 + 1e-12).sqrt() - t * &k * 0.5).clamp_min(0.0).square()
            }
            Integrator::Euler => {
                let mut cols = vec![u0];
                for _ in 1..steps {
                    let last = cols.last().expect("one column");
                    let next = (last - (last + 1e-12).sqrt() * &k * self.dt).clamp_min(0.0);
                    cols.push(next);
                }
                Tensor::cat(&cols, 1)
            }
        };
        &self.base + u * sigma
    }
    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        vec![
            self.log_k.double_value(&[]).exp(),
            self.base.double_value(&[]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn readings(values: &[f64]) -> Readings {
        Readings {
            values: values.to_vec(),
            positions: Vec::new(),
        }
    }

    #[test]
    fn scale_from_reference_frames_turns_latent_units_into_si() {
        let cal = Calibration {
            reference: vec![(0, 0, 0.07), (3, 9, 0.01)],
            g: 9.81,
            source: "flags".into(),
            ..Default::default()
        };
        // z = −40·h + 1 → α = −40, the empty tank's latent (base) is 1; k_latent = k·√40.
        let latents = [-40.0 * 0.07 + 1.0, -40.0 * 0.01 + 1.0];
        let (rows, warnings) =
            Torricelli.derive(&[0.0128 * 40f64.sqrt(), 1.0], &cal, &readings(&latents));
        assert!(warnings.is_empty());
        assert_eq!(rows[0].name, "k");
        assert!((rows[0].estimate - 0.0128).abs() < 1e-12);
        // A latent bent by the law's own symmetry, √u = p + q·√h (here p = 0.05, q = 3, base
        // 0.2 with u = −(z − base)), still gives the SI k.
        let (p, q, k) = (0.05f64, 3.0f64, 0.0128);
        let latents = [0.07f64, 0.01].map(|h| 0.2 - (p + q * h.sqrt()).powi(2));
        let (rows, _) = Torricelli.derive(&[q * k, 0.2], &cal, &readings(&latents));
        assert!((rows[0].estimate - k).abs() < 1e-12, "{}", rows[0].estimate);
        let (rows, warnings) =
            Torricelli.derive(&[0.1, 0.2], &Calibration::default(), &Readings::default());
        assert_eq!(rows[0].units, "latent");
        assert!(warnings[0].contains("--reference"), "{warnings:?}");
    }
}
