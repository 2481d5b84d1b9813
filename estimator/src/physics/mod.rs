//! The physical models `estimate` fits. `model.rs` holds the `Model` trait (parameters,
//! defaults, block, starts, SI answers), `block.rs` the `PhysicsBlock` trait (the
//! differentiable rollout), and each model is one file listed once in `MODELS`; `--model`'s
//! values and help are generated from that list. Adding a model = a file and a line here.

pub mod block;
pub mod bounds;
pub mod constant_acceleration;
pub mod file;
pub mod hooks;
pub mod info;
pub mod led;
pub mod model;
pub mod ode;
pub mod oscillator;
pub mod pendulum;
pub(crate) mod smooth_map;
pub mod spectral;
pub mod spring;
pub mod torricelli;

pub use block::{BlockOptions, Clips, Integrator, PhysicsBlock, RolloutStart};
pub use bounds::Bounds;
pub use hooks::Implausible;
pub use info::{ModelInfo, ParamSpec, Picture, Settles};
pub use model::{Derived, Model, ModelRef};

/// Every model, in the order `--help` lists them.
pub static MODELS: &[&dyn Model] = &[
    &oscillator::DampedOscillator,
    &pendulum::Pendulum,
    &torricelli::Torricelli,
    &constant_acceleration::SLIDING_BLOCK,
    &led::Led,
    &constant_acceleration::FREE_FALL,
    &spring::Spring,
];

impl ModelRef {
    /// The model called `name`.
    pub fn by_name(name: &str) -> Option<ModelRef> {
        MODELS
            .iter()
            .find(|m| m.name() == name)
            .map(|m| ModelRef(*m))
    }

    /// A model given on the command line: a built-in model's name, or a model file
    /// (`FILE.toml`).
    pub fn parse(text: &str) -> Result<ModelRef, String> {
        if let Some(m) = ModelRef::by_name(text) {
            return Ok(m);
        }
        if text.ends_with(".toml") || std::path::Path::new(text).is_file() {
            return file::FileModel::load(std::path::Path::new(text)).map_err(|e| e.to_string());
        }
        Err(format!(
            "'{text}' is neither a model ({}) nor a model file (FILE.toml)",
            ModelRef::names()
        ))
    }

    /// Every model's name, for messages.
    pub fn names() -> String {
        MODELS
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_are_unique_and_parameters_consistent() {
        for m in MODELS {
            assert_eq!(ModelRef::by_name(m.name()).unwrap().name(), m.name());
            for p in m.parameters() {
                assert!(p.bounds.contains(p.start), "{}: {}", m.name(), p.name);
            }
            let (frames, dt) = m.table5_clip();
            assert!(frames >= 3 && dt > 0.0);
        }
        let mut names: Vec<_> = MODELS.iter().map(|m| m.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), MODELS.len());
    }

    /// Every system `gen` and `estimate` share has a model here with its facts, and the truth
    /// keys the model compares with are the system's.
    #[test]
    fn every_shared_system_is_a_model_with_its_facts() {
        for sys in physvid_shared::systems::SYSTEMS {
            let m = ModelRef::by_name(sys.model).unwrap_or_else(|| panic!("{}", sys.model));
            assert_eq!(m.table5_clip(), sys.clip, "{}", sys.model);
            assert_eq!(
                m.released_from_rest(),
                sys.released_from_rest,
                "{}",
                sys.model
            );
            let keys: Vec<&str> = m.info().law.truth.iter().map(|t| t.name).collect();
            assert_eq!(keys, sys.truth, "{}", sys.model);
        }
        assert_eq!(physvid_shared::systems::SYSTEMS.len(), MODELS.len());
    }
}
