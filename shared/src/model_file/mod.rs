//! Models from a file: a TOML file that states a system of ODEs (`[state]`), its learnable
//! parameters (`[parameters]`), what the latent observes (`[observed]`), the initial ranges `gen`
//! draws from (`[initial]`) and values derived from the parameters (`[derived]`). `load` reads
//! and checks it (every error names the file, the key and the problem; `parameters.rs` the
//! numeric tables `[parameters]` and `[initial]`); `system.rs` compiles it for integration with
//! exact Jacobians; `symmetry.rs` finds which parameters the latent's arbitrary scale and offset
//! (or a change of time unit) move.

pub mod curved;
pub mod expr;
mod parameters;
mod read;
#[cfg(test)]
mod read_tests;
pub mod symmetry;
pub mod system;

pub use read::load;
pub use symmetry::Symmetries;
pub use system::{AtParams, CompiledSystem};

use expr::Expr;
use std::path::PathBuf;

/// A problem with a model file: the file, the key (`state.v`, `parameters.a.min`, …) and what
/// is wrong, shown on one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {key}: {problem}", file.display())]
pub struct ModelFileError {
    pub file: PathBuf,
    pub key: String,
    pub problem: String,
}

/// A learnable parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    pub name: String,
    pub start: f64,
    /// Lower and upper bounds (`positive = true` is a lower bound of 0, excluded).
    pub min: Option<f64>,
    pub max: Option<f64>,
    pub unit: Option<String>,
}

/// A value computed from the parameters for the report (e.g. a length from g/L).
#[derive(Debug, Clone, PartialEq)]
pub struct DerivedDef {
    pub name: String,
    /// Over the parameters' variable numbers (see [`ModelFile::variable`]).
    pub expr: Expr,
    pub unit: Option<String>,
}

/// A checked model file. Variables are numbered states first, then parameters, then `t`.
#[derive(Debug, Clone)]
pub struct ModelFile {
    pub path: PathBuf,
    /// The file's text as read (what `gen` copies into meta.json, so the data set describes
    /// its own model).
    pub source: String,
    pub name: String,
    pub description: String,
    /// The encoder the file asks for (`small`, `paper`, `linear`, `keypoints`), if any.
    pub encoder: Option<String>,
    pub parameters: Vec<Parameter>,
    /// State variables in the file's order, with d/dt of each.
    pub states: Vec<String>,
    pub equations: Vec<Expr>,
    /// Each equation as the file writes it (for messages).
    pub equation_texts: Vec<String>,
    /// The state variables the latent's coordinates observe, in order.
    pub observed: Vec<usize>,
    /// Ranges `gen` draws each state's initial value from (`None`: not given).
    pub initial: Vec<Option<(f64, f64)>>,
    pub derived: Vec<DerivedDef>,
    /// What the KL term holds near N(0, 1): expressions of the observed variables (`[observed]
    /// kl`, e.g. a relative position); empty: each latent coordinate.
    pub kl: Vec<Expr>,
}

impl ModelFile {
    /// The variable number of `name` (a state, a parameter or `t`).
    pub fn variable(&self, name: &str) -> Option<usize> {
        let (n, m) = (self.states.len(), self.parameters.len());
        if let Some(i) = self.states.iter().position(|s| s == name) {
            return Some(i);
        }
        if let Some(j) = self.parameters.iter().position(|p| p.name == name) {
            return Some(n + j);
        }
        (name == "t").then_some(n + m)
    }

    /// An error about `key` of this file.
    pub fn error(&self, key: impl Into<String>, problem: impl Into<String>) -> ModelFileError {
        ModelFileError {
            file: self.path.clone(),
            key: key.into(),
            problem: problem.into(),
        }
    }

    /// The parameters' starts, in order.
    pub fn starts(&self) -> Vec<f64> {
        self.parameters.iter().map(|p| p.start).collect()
    }

    /// The derived values at parameters `p`.
    pub fn derived_values(&self, p: &[f64]) -> Vec<f64> {
        let n = self.states.len();
        let mut vars = vec![0.0; n + p.len() + 1];
        vars[n..n + p.len()].copy_from_slice(p);
        self.derived.iter().map(|d| d.expr.eval(&vars)).collect()
    }

    /// The order of the system per observed variable (2 for x, v per position), at least 1.
    pub fn order(&self) -> usize {
        (self.states.len() / self.observed.len().max(1)).max(1)
    }
}

/// An example file, parsed the way a user's is (for tests and documentation).
#[cfg(test)]
pub(crate) fn parse_text(text: &str) -> Result<ModelFile, ModelFileError> {
    read::parse_file(std::path::Path::new("test.toml"), text)
}

/// A model file's text from elsewhere than a file of its own (meta.json's `model.file`), checked
/// as [`load`] checks a file; `origin` names where it came from in errors.
pub fn parse(origin: &std::path::Path, text: &str) -> Result<ModelFile, ModelFileError> {
    read::parse_file(origin, text)
}
