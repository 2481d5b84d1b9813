//! The physical systems both programs know, one record each: the model's name (gen's meta.json
//! `model.name`, estimate's `--model`), its law in words, appendix Table 5's clip, whether it
//! starts from rest at the recording's start, and the true values a data set of it carries.
//! `gen`'s scenes and `estimate`'s models both read these, so the two registries cannot drift
//! apart (tests in each check they agree).

/// One physical system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct System {
    /// The model's name.
    pub model: &'static str,
    /// The governing equation, in words.
    pub law: &'static str,
    /// Appendix Table 5's frames per clip and dt (s) (the paper's synthetic sets for the
    /// oscillator, PAIG's clips for the spring).
    pub clip: (usize, f64),
    /// Motion from rest at the start of the recording: each clip's start time since the
    /// release is part of the data.
    pub released_from_rest: bool,
    /// The true values a data set of the system carries in meta.json's `model.parameters`,
    /// among them those `estimate` compares its answers with.
    pub truth: &'static [&'static str],
}

pub const DAMPED_OSCILLATOR: System = System {
    model: "damped-oscillator",
    law: "z'' + γ1·z' + γ0·z = 0",
    clip: (20, 0.2),
    released_from_rest: false,
    truth: &["gamma0", "gamma1"],
};

pub const PENDULUM: System = System {
    model: "pendulum",
    law: "θ'' = −(g/L)·sin θ − ζ·θ'",
    clip: (20, 0.1),
    released_from_rest: false,
    truth: &["length", "damping"],
};

pub const TORRICELLI: System = System {
    model: "torricelli",
    law: "h' = −k·√h",
    clip: (20, 1.0),
    released_from_rest: false,
    truth: &["k"],
};

pub const SLIDING_BLOCK: System = System {
    model: "sliding-block",
    law: "s'' = g·(sin α − μ·cos α)",
    clip: (10, 1.0 / 30.0),
    released_from_rest: true,
    truth: &["acceleration", "mu"],
};

pub const LED: System = System {
    model: "led",
    law: "I' = −γ·I",
    clip: (20, 1.0 / 60.0),
    released_from_rest: false,
    truth: &["gamma"],
};

pub const FREE_FALL: System = System {
    model: "free-fall",
    law: "h'' = g",
    clip: (4, 1.0 / 30.0),
    released_from_rest: true,
    truth: &["g"],
};

pub const SPRING: System = System {
    model: "spring",
    law: "x₁'' = k·(|d| − l)·d̂, x₂'' = −x₁'', d = x₂ − x₁",
    clip: (12, 0.3),
    released_from_rest: false,
    truth: &["k", "rest_length"],
};

/// Every system, in the order the programs list them.
pub static SYSTEMS: &[&System] = &[
    &DAMPED_OSCILLATOR,
    &PENDULUM,
    &TORRICELLI,
    &SLIDING_BLOCK,
    &LED,
    &FREE_FALL,
    &SPRING,
];

/// The system called `model`.
pub fn by_model(model: &str) -> Option<&'static System> {
    SYSTEMS.iter().copied().find(|s| s.model == model)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_clips_sensible() {
        let mut names: Vec<&str> = SYSTEMS.iter().map(|s| s.model).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), SYSTEMS.len());
        for s in SYSTEMS {
            assert!(s.clip.0 >= 3 && s.clip.1 > 0.0, "{}", s.model);
            assert_eq!(by_model(s.model), Some(*s));
        }
    }
}
