//! The model flags: which law (`--model`, its values generated from `physics::MODELS`), dt,
//! starting values, the calibration (`--reference`, parsed in `reference.rs`, `--incline-deg`,
//! `--g`) and the integrator.

use super::positive;
use super::reference::{parse_reference, ReferencePoints};
use crate::calibration::{Plane, Stick, DEFAULT_G};
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
    /// "Choosing the model"; on a video whose object's track oscillates clearly, the
    /// oscillator on the track's span instead, unless --start or --end is given; where it
    /// accelerates at a constant rate down or along the picture, the fall, or off the vertical
    /// (or with --incline-deg) the slide). Taken from meta.json for a data set; without it, a
    /// recording or a bare .npy is auto.
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
    /// (as --start uses), SECONDSs=VALUE (e.g. 3.0s=0.079,20.5s=0.012; for a fall or slide,
    /// a time just after the part kept, such as the floor at the impact, is read where the law
    /// carries it; beside --stick or --plane, one reading is enough: it fixes the origin of the
    /// track's distances); for the spring, both bodies' pixel positions, CLIP:FRAME=X1/Y1/X2/Y2
    /// (taken from meta.json for gen data).
    #[arg(long, value_parser = parse_reference, value_name = "CLIP:FRAME=VALUE|SECONDSs=VALUE,...")]
    pub reference: Option<ReferencePoints>,
    /// A length in the picture, as a lab sets its video's scale: two points of the displayed
    /// frame (pixels from its top left, as an image viewer shows them) and the distance between
    /// them in metres, X1,Y1:X2,Y2=METRES (e.g. the ends of a metre stick, 284,45.5:284,446=1).
    /// The object's track is read in metres: a fall's g or a roll's acceleration in SI with no
    /// --reference, whose readings the track then gives the latent route, and an oscillation's
    /// amplitude. report.html and frame.jpg draw it on a frame of the recording; on the
    /// report's, two clicks and a typed length write one to copy.
    #[arg(long, value_parser = Stick::parse, value_name = "X1,Y1:X2,Y2=METRES")]
    pub stick: Option<Stick>,
    /// For a camera tilted to the plane of the motion (where one stick cannot carry the scale:
    /// the far part of the path is drawn smaller): the four corners of a rectangle in that
    /// plane (pixels of the displayed frame, in order around it: the first to the second along
    /// its width, the second to the third along its height) and its width and height in metres,
    /// X1,Y1:X2,Y2:X3,Y3:X4,Y4=WIDTHxHEIGHT (e.g. the corners of a door or a board behind the
    /// fall, 80,30:160,30:143,134:71,134=4x6). The object's track is read on that plane in
    /// metres, as with --stick; report.html draws the rectangle on a frame.
    #[arg(long, value_parser = Plane::parse, value_name = "X1,Y1:…:X4,Y4=WxH", conflicts_with = "stick")]
    pub plane: Option<Plane>,
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
    #[arg(long, value_enum, default_value_t = Integrator::default())]
    pub integrator: Integrator,
    /// damped-oscillator: where each clip's rollout starts: fit (the initial state that fits
    /// the whole clip in least squares, robust to pixel noise) or frames (the first two encoded
    /// frames, the paper's). The pendulum always fits its start; first-order and
    /// constant-acceleration blocks start from the first frame.
    #[arg(long, value_enum, default_value_t = RolloutStart::default())]
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
    match m.info().law.file {
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

    #[test]
    fn init_text_parses_and_rejects_garbage() {
        assert_eq!(
            parse_init("gamma0=10, gamma1=0.5").unwrap().0,
            vec![("gamma0".to_string(), 10.0), ("gamma1".to_string(), 0.5)]
        );
        assert!(parse_init("gamma0").is_err());
        assert!(parse_init("gamma0=x").is_err());
    }
}
