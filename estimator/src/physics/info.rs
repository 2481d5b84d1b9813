//! `ModelInfo`: the facts about one model, grouped by who reads them (the law, the footage it
//! needs, its calibration, its training), and the parameters and truth keys they list.

use super::bounds::Bounds;
use crate::calibration::CalibrationInput;
use crate::encoder::EncoderKind;
use physvid_shared::systems::System;

/// One learnable parameter of a block.
#[derive(Debug, Clone, Copy)]
pub struct ParamSpec {
    pub name: &'static str,
    /// The default start (`--init` overrides it).
    pub start: f64,
    /// The interval it is learned in (positive: (0, ∞), as a logarithm); the start must lie
    /// inside.
    pub bounds: Bounds,
    /// How the early stop judges that it has converged.
    pub settles: Settles,
}

/// How a parameter's convergence is judged (see `train::Trainer`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Settles {
    /// Relative to its own value.
    Relative,
    /// An offset in latent units, often near 0: against the latent's spread (1, which the KL
    /// term holds).
    LatentOffset,
    /// Not judged: a map from latent to physical units refitted from reference frames at every
    /// step, which moves with the encoder while the physical parameters hold the answer.
    Map,
}

impl Settles {
    /// What a change of a parameter whose value is about `v` is measured against: its own
    /// size, the latent's spread (1) for an offset smaller than it, nothing for a map.
    pub fn scale(self, v: f64) -> Option<f64> {
        match self {
            Settles::Relative => Some(v.abs()),
            Settles::LatentOffset => Some(v.abs().max(1.0)),
            Settles::Map => None,
        }
    }
}

impl ParamSpec {
    /// A parameter `name` starting at `start`, learned as a logarithm when `positive`.
    pub const fn new(name: &'static str, start: f64, positive: bool) -> ParamSpec {
        ParamSpec {
            name,
            start,
            bounds: if positive {
                Bounds::POSITIVE
            } else {
                Bounds::FREE
            },
            settles: Settles::Relative,
        }
    }

    /// An offset in latent units (see [`Settles::LatentOffset`]).
    pub const fn offset(name: &'static str, start: f64) -> ParamSpec {
        ParamSpec {
            settles: Settles::LatentOffset,
            ..ParamSpec::new(name, start, false)
        }
    }

    /// A parameter of the latent-to-physical map (see [`Settles::Map`]).
    pub const fn map(name: &'static str, start: f64, positive: bool) -> ParamSpec {
        ParamSpec {
            settles: Settles::Map,
            ..ParamSpec::new(name, start, positive)
        }
    }
}

/// A ground-truth value a model's report is compared with (meta.json's `model.parameters`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TruthKey {
    pub name: &'static str,
    /// No such system has it at zero or below (a rate γ0, a length).
    pub positive: bool,
}

impl TruthKey {
    /// A value that is > 0 for every such system.
    pub const fn positive(name: &'static str) -> TruthKey {
        TruthKey {
            name,
            positive: true,
        }
    }

    /// A value of either sign.
    pub const fn signed(name: &'static str) -> TruthKey {
        TruthKey {
            name,
            positive: false,
        }
    }
}

/// The facts about a model, one record per model (its file's `INFO`), in four groups: the
/// law, what footage of it must show, how its answers reach physical units, how its block is
/// trained.
#[derive(Debug, Clone, Copy)]
pub struct ModelInfo {
    pub law: Law,
    pub footage: Footage,
    pub calibration: Calibrates,
    pub training: Training,
}

/// What the law is: its name, equation, parameters and the values a report compares with.
#[derive(Debug, Clone, Copy)]
pub struct Law {
    /// The `--model` value (and meta.json's `model.name`).
    pub name: &'static str,
    /// The equation and its parameters, one line for `--help`.
    pub help: &'static str,
    /// The block's learnable parameters, in its order.
    pub parameters: &'static [ParamSpec],
    /// Numbers per frame of the latent (1: one quantity; the spring: x, y of two bodies).
    pub latent_dims: usize,
    /// The ground-truth values its report compares with (meta.json checks against them).
    pub truth: &'static [TruthKey],
    /// The model file it was read from (`None`: built in).
    pub file: Option<&'static str>,
}

/// What footage of the system must show, and how it is cut into clips.
#[derive(Debug, Clone, Copy)]
pub struct Footage {
    /// Appendix Table 5's frames per clip and dt (s) for a recording of this system.
    pub table5_clip: (usize, f64),
    /// Motion from rest at the start of the recording: clip start times since the release pin
    /// the latent (from meta.json, or a recording's release found in its frames).
    pub released_from_rest: bool,
    /// The smallest frame side (pixels) that can show the system (0: any), with what needs it.
    pub min_frame: (usize, &'static str),
    /// The longest dt (s) the block can integrate (∞: any within [`DT_RANGE`]), with why.
    pub max_dt: (f64, &'static str),
    /// What the model assumes of the picture as a function of the modelled quantity, and
    /// why: the verdict checks the frames (`verdict/premise.rs`).
    pub picture: Option<Picture>,
    /// What the law reads from the motion swinging back, when it is a law of swings (a
    /// pendulum's length from its period): the verdict checks that the latent turns back
    /// within clips.
    pub swings: Option<&'static str>,
}

/// A model's premise about the picture, with what makes it so.
#[derive(Debug, Clone, Copy)]
pub enum Picture {
    /// Every pixel is an affine function of the quantity (an LED's brightness scales its light).
    Affine(&'static str),
    /// The quantity moves an edge across the picture (a tank's water line), which no affine
    /// function of it draws.
    MovingEdge(&'static str),
}

/// How the answers reach physical units.
#[derive(Debug, Clone, Copy)]
pub struct Calibrates {
    /// The calibrations its answers read; the others are refused for it.
    pub inputs: &'static [CalibrationInput],
    /// The block reads the latent's map from reference frames during training.
    pub in_training: bool,
    /// What its reference values are when they cannot be below zero (`None`: any sign).
    pub nonnegative_reference: Option<&'static str>,
    /// The block's rollout runs past a clip's last frame by its law alone (a constant
    /// acceleration from the clip's first latents): a `--reference` time a little after the
    /// part kept (the floor at a fall's impact) is read on it (`RecordingSummary::clip_frame_at`).
    pub reads_past_end: bool,
}

/// How the block is trained, and what it offers beyond the exact rollout.
#[derive(Debug, Clone, Copy)]
pub struct Training {
    /// The encoder that makes the latent identifiable for this law, and why, when the model
    /// chose it itself (a model file without an `encoder` line; reported with the answer).
    pub encoder: EncoderKind,
    pub encoder_note: Option<&'static str>,
    /// Early-stop patience (epochs without improvement).
    pub patience: usize,
    /// The convergence stop's band: training ends when every parameter stayed within this
    /// fraction of its value (offsets: of the latent's spread; maps refitted from references
    /// are not judged) over a window of half the patience.
    pub converged_spread: f64,
    /// The block offers an ODE residual for `--loss residual+floor`.
    pub supports_residual: bool,
    /// The paper's Euler step exists for the block (`--integrator euler`).
    pub has_euler: bool,
}

pub use physvid_shared::dynamics::DT_RANGE;

impl Footage {
    /// Footage cut into `table5_clip`s, of any frame size and dt, not from rest.
    pub const fn of(table5_clip: (usize, f64)) -> Footage {
        Footage {
            table5_clip,
            released_from_rest: false,
            min_frame: (0, ""),
            max_dt: (f64::INFINITY, ""),
            picture: None,
            swings: None,
        }
    }
}

impl Calibrates {
    /// Answers in the latent's units: no calibration read.
    pub const NONE: Calibrates = Calibrates {
        inputs: &[],
        in_training: false,
        nonnegative_reference: None,
        reads_past_end: false,
    };

    /// Answers that read `inputs`, after training.
    pub const fn by(inputs: &'static [CalibrationInput]) -> Calibrates {
        Calibrates {
            inputs,
            ..Calibrates::NONE
        }
    }

    /// The same, its references also read past the part kept ([`Calibrates::reads_past_end`]).
    pub const fn past_end(self) -> Calibrates {
        Calibrates {
            reads_past_end: true,
            ..self
        }
    }
}

impl Training {
    /// The defaults most models share: the small encoder, patience 30, a band of 0.4 %, the
    /// Euler step and no residual loss.
    pub const DEFAULT: Training = Training {
        encoder: EncoderKind::Small,
        encoder_note: None,
        patience: 30,
        converged_spread: 4e-3,
        supports_residual: false,
        has_euler: true,
    };
}

impl ModelInfo {
    /// A built-in model of `system` (its name, Table 5's clip and whether it starts from rest
    /// come from the record `gen` shares), with the defaults most share.
    pub const fn of(
        system: &System,
        help: &'static str,
        parameters: &'static [ParamSpec],
        truth: &'static [TruthKey],
    ) -> ModelInfo {
        let info = ModelInfo::new(system.model, help, parameters, system.clip);
        ModelInfo {
            law: Law { truth, ..info.law },
            footage: Footage {
                released_from_rest: system.released_from_rest,
                ..info.footage
            },
            ..info
        }
    }

    /// A model with the defaults most share: one latent number, no calibration, the default
    /// training.
    pub const fn new(
        name: &'static str,
        help: &'static str,
        parameters: &'static [ParamSpec],
        table5_clip: (usize, f64),
    ) -> ModelInfo {
        ModelInfo {
            law: Law {
                name,
                help,
                parameters,
                latent_dims: 1,
                truth: &[],
                file: None,
            },
            footage: Footage::of(table5_clip),
            calibration: Calibrates::NONE,
            training: Training::DEFAULT,
        }
    }
}
