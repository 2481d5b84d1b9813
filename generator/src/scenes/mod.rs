//! The scenes `gen` renders: the `Scene` trait and `SCENES`, the one list of them (the
//! `--scenario` values and their help are generated from it). A scene knows its dynamics (the
//! trajectory of the physical quantity z each clip shows), its picture, its parameters and the
//! calibration a user would measure. Two families share most of their code: the damped
//! oscillator's disc scenes (`disc.rs`: intensity, position, scale) and the Delfys75 systems
//! (`delfys.rs`: pendulum, torricelli, sliding-block, led, free-fall); the two-body spring of
//! appendix A.5 (`spring.rs`) implements `Scene` itself, and so does `file.rs`, a model file's
//! system drawn on a disc picture (`gen --model`). Adding a scene = a file implementing
//! `DiscPicture`, `DelfysSystem` or `Scene`, and a line in `SCENES`.

mod delfys;
mod disc;
pub mod file;
pub mod free_fall;
pub mod intensity;
pub mod led;
pub mod pendulum;
pub mod position;
pub mod rod;
pub mod scale;
pub mod sliding_block;
pub mod spring;
mod spring_picture;
pub mod torricelli;

use crate::error::ConfigError;
use crate::render::Canvas;
use physvid_shared::{Calibration, SampleTruth};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;

pub use delfys::{reference_points, Delfys, DelfysSystem, SystemInfo, G, REFERENCE_FRACTIONS};
pub use disc::{DiscPicture, DiscScene, PictureInfo};

/// The least phase a clip spans (rad: ω·(T−1)·dt, about 1 % of a period) for the oscillating
/// scenes: below it the frames barely differ and nothing can be learned from them.
pub const MIN_PHASE_SPAN: f64 = 0.05;

/// Parameters of a scene by name (SI units): the oscillator's omega and zeta, or a Delfys75
/// system's Table 4 values after `--setting` and `--set`.
pub type Params = BTreeMap<String, f64>;

/// Parameters from name/value pairs.
pub fn params(pairs: &[(&str, f64)]) -> Params {
    pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

/// A scene: how a clip's physical quantity evolves and how it is drawn.
pub trait Scene: Sync {
    /// The `--scenario` value.
    fn name(&self) -> &'static str;
    /// One line for `--help`.
    fn help(&self) -> &'static str;
    /// The `estimate --model` that fits it (meta.json's `model.name`).
    fn model_name(&self) -> &'static str;
    /// The model file's text where the scene draws one (meta.json's `model.file`).
    fn model_source(&self) -> Option<&str> {
        None
    }
    /// Frames per clip and dt (s) when the flags do not say.
    fn default_clip(&self) -> (usize, f64);
    /// Parameters for `--setting` (1, 2 or 3; the disc scenes have one).
    fn params(&self, setting: u8) -> Params;
    /// Whether `--setting 1|2|3` chooses among different parameters (appendix Table 4's
    /// columns).
    fn has_settings(&self) -> bool {
        let (a, b, c) = (self.params(1), self.params(2), self.params(3));
        a != b || b != c
    }
    /// Whether `--set NAME=VALUE` changes the parameters (otherwise they have flags of their own).
    fn accepts_set(&self) -> bool;
    /// Checks the parameters against physics, the clip and the frame; errors name the flag to
    /// change.
    fn validate(&self, p: &Params, frames: usize, dt: f64, size: usize) -> Result<(), ConfigError>;
    /// Numbers per frame of the latent (1: one physical quantity).
    fn latent_dims(&self) -> usize {
        1
    }
    /// Colour channels of the frames (1: grey; `color` asks for the scene's colour version).
    fn channels(&self, _color: bool) -> usize {
        1
    }
    /// Frame width and height when `--size` does not say.
    fn default_size(&self) -> usize {
        50
    }
    /// Draws one clip from `rng` for `size`×`size` frames: its ground truth and the physical
    /// quantity at each frame (`latent_dims` numbers per frame, frame-major).
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
        size: usize,
    ) -> (SampleTruth, Vec<f64>);
    /// Draws the scene for the frame's latent `z` into `out` (channels × size² values in
    /// [0, 1], channel-major).
    fn render(&self, p: &Params, z: &[f64], size: usize, canvas: &mut Canvas, out: &mut [f32]);
    /// meta.json's `latent_mapping`: what z is and how it shows, in words.
    fn mapping_text(&self) -> &'static str;
    /// meta.json's `sampling`: how each clip's draws are made, in words.
    fn sampling_text(&self) -> &'static str;
    /// meta.json's `model.parameters`: the true values `estimate` is to recover (SI).
    fn model_parameters(&self, p: &Params) -> Params;
    /// What a user would measure in the scene (empty for the disc scenes), from every clip's
    /// latents.
    fn calibration(&self, p: &Params, size: usize, latents: &[Vec<f64>]) -> Calibration;
    /// The (virtual) camera's frame rate written to meta.json, if the scene has a camera.
    fn fps(&self, dt: f64) -> Option<f64>;
    /// Whether the recording starts at a release from rest (then meta.json gets each clip's
    /// start time since it).
    fn released_from_rest(&self) -> bool;
    /// The disc picture of a damped-oscillator scene, which a model file's system can be drawn
    /// on instead (`gen --model FILE.toml`).
    fn picture(&self) -> Option<&dyn DiscPicture> {
        None
    }
}

/// Every scene, in the order `--help` lists them.
pub static SCENES: &[&dyn Scene] = &[
    &DiscScene(intensity::Intensity),
    &DiscScene(position::Position),
    &DiscScene(scale::Scale),
    &DiscScene(rod::Rod),
    &Delfys(pendulum::Pendulum),
    &Delfys(torricelli::Torricelli),
    &Delfys(sliding_block::SlidingBlock),
    &Delfys(led::Led),
    &Delfys(free_fall::FreeFall),
    &spring::Spring,
];

/// A scene of [`SCENES`], compared and printed by name.
#[derive(Clone, Copy)]
pub struct SceneRef(pub &'static dyn Scene);

impl SceneRef {
    /// The scene called `name`.
    pub fn by_name(name: &str) -> Option<SceneRef> {
        SCENES
            .iter()
            .find(|s| s.name() == name)
            .map(|s| SceneRef(*s))
    }
}

impl std::ops::Deref for SceneRef {
    type Target = dyn Scene;
    fn deref(&self) -> &(dyn Scene + 'static) {
        self.0
    }
}

impl PartialEq for SceneRef {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl std::fmt::Debug for SceneRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::fmt::Display for SceneRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_found() {
        for s in SCENES {
            assert_eq!(SceneRef::by_name(s.name()).unwrap().name(), s.name());
        }
        let mut names: Vec<_> = SCENES.iter().map(|s| s.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), SCENES.len());
        assert!(SceneRef::by_name("wobble").is_none());
    }

    /// Every scene draws a system `estimate` knows, with its clip and release, and writes the
    /// true values the system's model compares with.
    #[test]
    fn every_scene_draws_a_shared_system() {
        for s in SCENES {
            let sys = physvid_shared::systems::by_model(s.model_name())
                .unwrap_or_else(|| panic!("{}: {}", s.name(), s.model_name()));
            assert_eq!(s.default_clip(), sys.clip, "{}", s.name());
            assert_eq!(
                s.released_from_rest(),
                sys.released_from_rest,
                "{}",
                s.name()
            );
            let truth = s.model_parameters(&s.params(1));
            for key in sys.truth {
                assert!(truth.contains_key(*key), "{}: no {key}", s.name());
            }
        }
    }
}
