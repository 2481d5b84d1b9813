//! The model flags: which law (`--model`, its values generated from `physics::MODELS`), dt,
//! starting values, the calibration (`--reference`, `--incline-deg`, `--g`) and the integrator.

use super::positive;
use crate::calibration::DEFAULT_G;
use crate::error::{input_error, EstimateError};
use crate::physics::{Integrator, ModelRef, RolloutStart, MODELS};
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};

/// The governing equation and how it is integrated and calibrated.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Model")]
pub struct ModelArgs {
    /// The governing equation (taken from meta.json when present; required for recordings).
    #[arg(long, value_parser = model_parser())]
    pub model: Option<ModelRef>,
    /// Seconds between frames (taken from meta.json when present).
    #[arg(long)]
    pub dt: Option<f64>,
    #[arg(long, value_parser = parse_init, value_name = "NAME=VALUE,...", help = init_help())]
    pub init: Option<InitValues>,
    /// Calibration for answers in SI units: the physical quantity (level, distance, …; the
    /// pendulum's angle in rad, which then fixes its angle scale) at two or more frames,
    /// CLIP:FRAME=VALUE[,...] (taken from meta.json for gen data).
    #[arg(long, value_parser = parse_reference, value_name = "CLIP:FRAME=VALUE,...")]
    pub reference: Option<ReferencePoints>,
    /// Sliding block: the incline's angle in degrees, for μ (taken from meta.json for gen data).
    #[arg(long)]
    pub incline_deg: Option<f64>,
    #[arg(long, help = format!(
        "Gravitational acceleration in m/s² for the pendulum's L and the block's μ (taken from \
         meta.json for gen data) [default: {DEFAULT_G}]"
    ))]
    pub g: Option<f64>,
    /// Physics integrator: exact (closed form, or RK4 with sub-steps for the pendulum), or the
    /// paper's Euler step (biased at large dt).
    #[arg(long, value_enum, default_value_t = Integrator::Exact)]
    pub integrator: Integrator,
    /// damped-oscillator: where each clip's rollout starts: fit (the initial state that fits
    /// the whole clip in least squares, robust to pixel noise) or frames (the first two encoded
    /// frames, the paper's). The pendulum always fits its start; first-order and
    /// constant-acceleration blocks start from the first frame.
    #[arg(long, value_enum, default_value_t = RolloutStart::Fit)]
    pub rollout_start: RolloutStart,
}

/// `--model`'s values with their equations, from the registry.
fn model_parser() -> impl TypedValueParser<Value = ModelRef> {
    let values: Vec<PossibleValue> = MODELS
        .iter()
        .map(|m| PossibleValue::new(m.name()).help(m.help()))
        .collect();
    PossibleValuesParser::new(values)
        .map(|name| ModelRef::by_name(&name).expect("a possible value names a model"))
}

fn init_help() -> String {
    let each: Vec<String> = MODELS
        .iter()
        .map(|m| {
            let p: Vec<String> = m
                .parameters()
                .iter()
                .map(|p| format!("{}={}", p.name, p.start))
                .collect();
            format!("{}: {}", m.name(), p.join(","))
        })
        .collect();
    format!(
        "Initial values of the block's parameters, NAME=VALUE[,NAME=VALUE] [default: {}]",
        each.join("; ")
    )
}

/// `--reference` values: CLIP:FRAME=VALUE triples.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferencePoints(pub Vec<(usize, usize, f64)>);

/// Parses `--reference 0:0=0.07,12:19=0.01` (clip:frame=physical value).
pub fn parse_reference(text: &str) -> Result<ReferencePoints, String> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|item| {
            let bad = || format!("'{item}' is not CLIP:FRAME=VALUE (e.g. 0:0=0.07,3:19=0.01)");
            let (at, v) = item.split_once('=').ok_or_else(bad)?;
            let (c, f) = at.split_once(':').ok_or_else(bad)?;
            Ok((
                c.trim().parse().map_err(|_| bad())?,
                f.trim().parse().map_err(|_| bad())?,
                v.trim().parse().map_err(|_| bad())?,
            ))
        })
        .collect::<Result<Vec<_>, String>>()
        .map(ReferencePoints)
}

/// `--init` values: NAME=VALUE pairs in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct InitValues(pub Vec<(String, f64)>);

/// Parses `--init` text such as `gamma0=10,gamma1=0.5`.
pub fn parse_init(text: &str) -> Result<InitValues, String> {
    physvid_shared::cli::parse_name_values(text)
        .map(InitValues)
        .map_err(|e| format!("{e} (e.g. gamma0=10,gamma1=0.5)"))
}

impl ModelArgs {
    /// Checks the flags that do not depend on the data.
    pub fn validate(&self) -> Result<(), EstimateError> {
        if let Some(dt) = self.dt {
            positive("--dt", dt)?;
        }
        if let Some(g) = self.g {
            positive("--g", g)?;
        }
        if let Some(deg) = self.incline_deg {
            if !(deg.is_finite() && deg > 0.0 && deg < 90.0) {
                return Err(input_error(format!(
                    "--incline-deg {deg}: must be an angle in (0, 90) degrees"
                )));
            }
        }
        for (name, v) in self.init_pairs() {
            if !v.is_finite() {
                return Err(input_error(format!(
                    "--init {name}={v}: must be a finite number"
                )));
            }
        }
        Ok(())
    }

    /// The `--init` pairs (none when the flag is absent).
    pub fn init_pairs(&self) -> &[(String, f64)] {
        self.init.as_ref().map_or(&[], |i| &i.0)
    }

    /// The `--reference` points (none when the flag is absent).
    pub fn reference_points(&self) -> &[(usize, usize, f64)] {
        self.reference.as_ref().map_or(&[], |r| &r.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn init_text_parses_and_rejects_garbage() {
        assert_eq!(
            parse_init("gamma0=10, gamma1=0.5").unwrap().0,
            vec![("gamma0".to_string(), 10.0), ("gamma1".to_string(), 0.5)]
        );
        assert!(parse_init("gamma0").is_err());
        assert!(parse_init("gamma0=x").is_err());
        assert_eq!(parse_reference("0:1=0.5").unwrap().0, vec![(0, 1, 0.5)]);
        assert!(parse_reference("0=0.5").is_err());
    }
}
