//! The model flags: which law (`--model`, its values generated from `physics::MODELS`), dt,
//! starting values, the calibration (`--reference`, `--incline-deg`, `--g`) and the integrator.

use super::positive;
use crate::calibration::DEFAULT_G;
use crate::error::{input_error, EstimateError};
use crate::physics::{Integrator, ModelRef, RolloutStart, MODELS};
use clap::builder::{PossibleValue, TypedValueParser};
use physvid_shared::cli::num;

/// The governing equation and how it is integrated and calibrated.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Model")]
pub struct ModelArgs {
    /// The governing equation: a built-in model, a model file FILE.toml (see README, "Your own
    /// model"), or auto (each candidate fitted, the one the evidence favours kept; see README,
    /// "Choosing the model"). Taken from meta.json for a data set; without it, a recording or
    /// a bare .npy is auto.
    #[arg(long, value_parser = model_parser(), value_name = "MODEL|FILE.toml|auto")]
    pub model: Option<ModelSpec>,
    /// A model file tried beside the built-in models when the model is chosen (--model auto,
    /// or none on a recording); repeatable.
    #[arg(long, value_parser = model_file_parser, value_name = "FILE.toml")]
    pub candidate: Vec<ModelRef>,
    /// Seconds between frames (taken from meta.json when present).
    #[arg(long)]
    pub dt: Option<f64>,
    #[arg(long, value_parser = parse_init, value_name = "NAME=VALUE,...", help = init_help())]
    pub init: Option<InitValues>,
    /// Calibration for answers in SI units: the physical quantity (level, distance, …; the
    /// pendulum's angle in rad, which then fixes its angle scale) at two or more frames,
    /// CLIP:FRAME=VALUE[,...], or for a recording at two or more times on its own timeline
    /// (as --start uses), SECONDSs=VALUE (e.g. 3.0s=0.079,20.5s=0.012); for the spring, both
    /// bodies' pixel positions, CLIP:FRAME=X1/Y1/X2/Y2 (taken from meta.json for gen data).
    #[arg(long, value_parser = parse_reference, value_name = "CLIP:FRAME=VALUE|SECONDSs=VALUE,...")]
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

/// `--model`'s value: one model, or the choice among candidates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModelSpec {
    Given(ModelRef),
    /// `--model auto`.
    Auto,
}

/// `--model`'s values: the registry's names with their equations (listed in `--help`), a
/// model file, or auto.
#[derive(Clone)]
struct ModelParser;

impl TypedValueParser for ModelParser {
    type Value = ModelSpec;
    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &std::ffi::OsStr,
    ) -> Result<ModelSpec, clap::Error> {
        let text = value.to_string_lossy();
        if text == "auto" {
            return Ok(ModelSpec::Auto);
        }
        ModelRef::parse(&text).map(ModelSpec::Given).map_err(|e| {
            let flag = arg.map_or("--model".into(), |a| a.to_string());
            clap::Error::raw(
                clap::error::ErrorKind::ValueValidation,
                format!("invalid value '{text}' for '{flag}': {e}\n"),
            )
            .with_cmd(cmd)
        })
    }
    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(
            MODELS
                .iter()
                .map(|m| PossibleValue::new(m.name()).help(m.help()))
                .chain([PossibleValue::new("auto").help(
                    "each candidate fitted (the built-in models of one latent number, and \
                     --candidate files), the one the evidence favours kept",
                )]),
        ))
    }
}

/// `--candidate`: a model file.
fn model_file_parser(text: &str) -> Result<ModelRef, String> {
    let m = ModelRef::parse(text)?;
    match m.info().file {
        Some(_) => Ok(m),
        None => Err(format!(
            "'{text}' is a built-in model, which the choice tries already; --candidate takes a model file (FILE.toml)"
        )),
    }
}

fn model_parser() -> ModelParser {
    ModelParser
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

/// `--reference` values: CLIP:FRAME=VALUE triples, SECONDSs=VALUE pairs (a recording's
/// timeline), and CLIP:FRAME=X1/Y1/X2/Y2 body positions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReferencePoints {
    pub values: Vec<(usize, usize, f64)>,
    /// (seconds on the recording's timeline, value).
    pub times: Vec<(f64, f64)>,
    pub positions: Vec<(usize, usize, Vec<f64>)>,
}

/// Parses `--reference 0:0=0.07,12:19=0.01` (clip:frame=physical value) and
/// `--reference 0:0=20/30/44/33` (clip:frame=positions separated by '/').
pub fn parse_reference(text: &str) -> Result<ReferencePoints, String> {
    let mut points = ReferencePoints::default();
    for item in text.split(',').filter(|s| !s.trim().is_empty()) {
        let bad = || {
            format!(
                "'{item}' is not CLIP:FRAME=VALUE, SECONDSs=VALUE or CLIP:FRAME=X1/Y1/X2/Y2 (e.g. 0:0=0.07,3:19=0.01 or 3.0s=0.079)"
            )
        };
        let (at, v) = item.split_once('=').ok_or_else(bad)?;
        if let Some(t) = at.trim().strip_suffix('s') {
            let t: f64 = t.trim().parse().map_err(|_| bad())?;
            let v: f64 = v.trim().parse().map_err(|_| bad())?;
            if !(t.is_finite() && t >= 0.0 && v.is_finite()) {
                return Err(format!(
                    "'{item}': the time must be >= 0 s and the value a finite number"
                ));
            }
            if points.times.iter().any(|&(t2, _)| t2 == t) {
                return Err(format!(
                    "'{item}': the time {t} s is given twice; give each once"
                ));
            }
            points.times.push((t, v));
            continue;
        }
        let (c, f) = at.split_once(':').ok_or_else(bad)?;
        let (c, f) = (
            c.trim().parse().map_err(|_| bad())?,
            f.trim().parse().map_err(|_| bad())?,
        );
        let numbers: Vec<f64> = v
            .split('/')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        if let Some(x) = numbers.iter().find(|x| !x.is_finite()) {
            return Err(format!("'{item}': {x} is not a finite number"));
        }
        let taken = points.values.iter().any(|p| (p.0, p.1) == (c, f))
            || points.positions.iter().any(|p| (p.0, p.1) == (c, f));
        if taken {
            return Err(format!(
                "'{item}': clip {c} frame {f} is given twice; give each frame once"
            ));
        }
        match numbers[..] {
            [v] => points.values.push((c, f, v)),
            _ => points.positions.push((c, f, numbers)),
        }
    }
    Ok(points)
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

/// The largest `--init` magnitude: squared (γ1², the pendulum's ω) it stays within single
/// precision.
const MAX_INIT: f64 = 1e15;

impl ModelArgs {
    /// Checks the flags that do not depend on the data.
    pub fn validate(&self) -> Result<(), EstimateError> {
        if let Some(dt) = self.dt {
            positive("--dt", dt)?;
        }
        if let Some(g) = self.g {
            positive("--g", g)?;
            if g > physvid_shared::meta::MAX_G {
                return Err(input_error(format!(
                    "--g {}: gravity beyond {} m/s² (the Sun's surface has 274); give it in m/s²",
                    num(g),
                    physvid_shared::meta::MAX_G
                )));
            }
        }
        if let Some(deg) = self.incline_deg {
            if !(deg.is_finite() && deg > 0.0 && deg < 90.0) {
                return Err(input_error(format!(
                    "--incline-deg {deg}: must be an angle in (0, 90) degrees"
                )));
            }
        }
        for (name, v) in self.init_pairs() {
            if !(v.is_finite() && v.abs() <= MAX_INIT) {
                return Err(input_error(format!(
                    "--init {name}={}: must be a finite number within ±{MAX_INIT:e} (training is in single precision)",
                    num(*v)
                )));
            }
        }
        Ok(())
    }

    /// The model `--model` names (none for auto or without the flag).
    pub fn given(&self) -> Option<ModelRef> {
        match self.model {
            Some(ModelSpec::Given(m)) => Some(m),
            _ => None,
        }
    }

    /// The `--init` pairs (none when the flag is absent).
    pub fn init_pairs(&self) -> &[(String, f64)] {
        self.init.as_ref().map_or(&[], |i| &i.0)
    }

    /// The `--reference` values (none when the flag is absent).
    pub fn reference_points(&self) -> &[(usize, usize, f64)] {
        self.reference.as_ref().map_or(&[], |r| &r.values)
    }

    /// The `--reference` times on a recording's timeline (none when the flag is absent).
    pub fn reference_times(&self) -> &[(f64, f64)] {
        self.reference.as_ref().map_or(&[], |r| &r.times)
    }

    /// The `--reference` body positions (none when the flag is absent).
    pub fn reference_positions(&self) -> &[(usize, usize, Vec<f64>)] {
        self.reference.as_ref().map_or(&[], |r| &r.positions)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, rng_seed: proptest::test_runner::RngSeed::Fixed(31), ..ProptestConfig::default() })]

        /// Any text parses or gives one message; distinct frames read back as written.
        #[test]
        fn references_parse_or_say_why(text in ".{0,60}") {
            if let Err(e) = parse_reference(&text) {
                prop_assert!(!e.is_empty() && !e.contains('\n'));
            }
        }

        #[test]
        fn distinct_frames_read_back(
            frames in proptest::collection::btree_map((0usize..50, 0usize..20), -1e6f64..1e6, 1..6),
        ) {
            let text: Vec<String> = frames.iter().map(|((c, f), v)| format!("{c}:{f}={v}")).collect();
            let p = parse_reference(&text.join(",")).unwrap();
            let expected: Vec<(usize, usize, f64)> = frames.iter().map(|(&(c, f), &v)| (c, f, v)).collect();
            prop_assert_eq!(p.values, expected);
        }
    }

    #[test]
    fn init_text_parses_and_rejects_garbage() {
        assert_eq!(
            parse_init("gamma0=10, gamma1=0.5").unwrap().0,
            vec![("gamma0".to_string(), 10.0), ("gamma1".to_string(), 0.5)]
        );
        assert!(parse_init("gamma0").is_err());
        assert!(parse_init("gamma0=x").is_err());
        assert_eq!(
            parse_reference("0:1=0.5").unwrap().values,
            vec![(0, 1, 0.5)]
        );
        let p = parse_reference("0:1=0.5,2:3=1/2/3.5/4").unwrap();
        assert_eq!(p.positions, vec![(2, 3, vec![1.0, 2.0, 3.5, 4.0])]);
        assert!(parse_reference("0=0.5").is_err());
        assert!(parse_reference("0:1=1/x").is_err());
        assert!(parse_reference("0:1=nan").is_err());
        let t = parse_reference("3.0s=0.079, 20.5s=0.012,1:2=0.5").unwrap();
        assert_eq!(t.times, vec![(3.0, 0.079), (20.5, 0.012)]);
        assert_eq!(t.values, vec![(1, 2, 0.5)]);
        assert!(parse_reference("-1s=0.5").is_err());
        assert!(parse_reference("0:1=0.5,0:1=0.5")
            .unwrap_err()
            .contains("twice"));
        assert!(parse_reference("3s=0.1,3.0s=0.2")
            .unwrap_err()
            .contains("twice"));
        assert!(parse_reference("xs=0.5").is_err());
    }
}
