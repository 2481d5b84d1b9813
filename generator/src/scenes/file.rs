//! A model file's system drawn on a disc scene (`gen --model FILE.toml --scenario
//! intensity|position|scale`): each clip's initial state drawn uniformly from the file's
//! `[initial]` ranges, the trajectory integrated by RK4, and the first observed variable x mapped
//! linearly onto the picture's z ∈ [−1, 1] by one map for the whole dataset (from a pass over
//! every clip's trajectory before rendering; recorded in meta.json with reference frames of
//! known x, so `estimate` can calibrate).

use super::{reference_points, DiscPicture, Params, Scene};
use crate::error::{invalid, ConfigError};
use crate::render::Canvas;
use crate::sampling::sample_rng;
use physvid_shared::cli::num;
use physvid_shared::model_file::{CompiledSystem, ModelFile};
use physvid_shared::{Calibration, SampleTruth};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// RK4 sub-steps per frame.
const SUBSTEPS: usize = 32;

/// A model file on a disc picture, with the map x = centre + half·z.
#[derive(Clone)]
pub struct FileScene {
    file: ModelFile,
    /// The file's name (meta.json's model).
    name: &'static str,
    system: CompiledSystem,
    picture: &'static dyn DiscPicture,
    map: (f64, f64),
    mapping: &'static str,
    sampling: &'static str,
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

impl FileScene {
    /// The scene of `file` on `picture`, with the identity map (z = x) until
    /// [`FileScene::with_map`] gives the one fitted to the clips ([`FileScene::fit_map`]).
    pub fn new(
        file: ModelFile,
        picture: &'static dyn DiscPicture,
    ) -> Result<FileScene, ConfigError> {
        if file.observed.len() != 1 {
            return Err(invalid(
                "--model",
                file.path.display(),
                format!(
                    "observes {} variables; gen draws one on the disc scenes (latent = [\"x\"])",
                    file.observed.len()
                ),
            ));
        }
        if let Some(i) = file.initial.iter().position(Option::is_none) {
            return Err(invalid(
                "--model",
                file.path.display(),
                format!("initial.{}: gen needs a range [min, max] for every state variable to draw clips from", file.states[i]),
            ));
        }
        let sampling = leak(format!(
            "each state variable's initial value uniform in its [initial] range, in the order {}, from ChaCha8 stream i (seeded with --seed) for sample i, then the pixel noise; RK4 with {SUBSTEPS} steps per frame",
            file.states.join(", ")
        ));
        let scene = FileScene {
            system: CompiledSystem::new(&file),
            name: leak(file.name.clone()),
            file,
            picture,
            map: (0.0, 1.0),
            mapping: "",
            sampling,
        };
        Ok(scene.with_map((0.0, 1.0)))
    }

    /// The same scene with the map `(centre, half)`.
    pub fn with_map(&self, map: (f64, f64)) -> FileScene {
        let x = &self.file.states[self.file.observed[0]];
        let mapping = leak(format!(
            "{}; z = (x - {}) / {} for the model file's observed variable x = {x}",
            self.picture.info().mapping_text,
            num(map.0),
            num(map.1)
        ));
        FileScene {
            map,
            mapping,
            ..self.clone()
        }
    }

    fn parameter_values(&self, p: &Params) -> Vec<f64> {
        self.file.parameters.iter().map(|q| p[&q.name]).collect()
    }

    /// One clip's initial state and observed trajectory.
    fn clip(
        &self,
        p: &[f64],
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
    ) -> (Vec<f64>, Vec<f64>) {
        let x0: Vec<f64> = self
            .file
            .initial
            .iter()
            .map(|r| {
                let (lo, hi) = r.unwrap_or((0.0, 0.0));
                if hi > lo {
                    rng.random_range(lo..hi)
                } else {
                    lo
                }
            })
            .collect();
        let n = self.system.n;
        let o = self.file.observed[0];
        let traj = self.system.trajectory(p, &x0, 0.0, dt, frames, SUBSTEPS);
        (x0, traj.chunks(n).map(|s| s[o]).collect())
    }

    /// The map (centre, half) that takes every clip's observed variable onto [−1, 1], from all
    /// `samples` clips of `seed` (the same draws the rendering makes).
    pub fn fit_map(
        &self,
        p: &Params,
        samples: usize,
        seed: u64,
        frames: usize,
        dt: f64,
    ) -> Result<(f64, f64), ConfigError> {
        let q = self.parameter_values(p);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..samples {
            let (_, xs) = self.clip(&q, &mut sample_rng(seed, i), frames, dt);
            if let Some(k) = xs.iter().position(|v| !v.is_finite() || v.abs() > 1e12) {
                return Err(invalid(
                    "--set",
                    self.describe(p),
                    format!("clip {i} diverges by frame {k} (the observed variable leaves ±1e12): the motion blows up at these parameters and [initial] ranges"),
                ));
            }
            for x in xs {
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
        if hi - lo <= 1e-9 * hi.abs().max(lo.abs()).max(1e-300) {
            return Err(invalid(
                "--set",
                self.describe(p),
                format!("the observed variable does not move (it stays at {}): nothing to see in the frames", num(lo)),
            ));
        }
        Ok((0.5 * (lo + hi), 0.5 * (hi - lo)))
    }

    fn describe(&self, p: &Params) -> String {
        let pairs: Vec<String> = self
            .file
            .parameters
            .iter()
            .map(|q| format!("{}={}", q.name, num(p[&q.name])))
            .collect();
        pairs.join(",")
    }
}

impl Scene for FileScene {
    fn name(&self) -> &'static str {
        self.picture.info().name
    }
    fn help(&self) -> &'static str {
        self.picture.info().help
    }
    fn model_name(&self) -> &'static str {
        self.name
    }
    fn model_source(&self) -> Option<&str> {
        Some(&self.file.source)
    }
    fn default_clip(&self) -> (usize, f64) {
        (20, 0.2)
    }
    fn params(&self, _setting: u8) -> Params {
        self.file
            .parameters
            .iter()
            .map(|q| (q.name.clone(), q.start))
            .collect()
    }
    fn accepts_set(&self) -> bool {
        true
    }
    /// Finite values within the file's bounds (outside them `estimate` could not reach them).
    fn validate(
        &self,
        p: &Params,
        _frames: usize,
        _dt: f64,
        _size: usize,
    ) -> Result<(), ConfigError> {
        for q in &self.file.parameters {
            let v = p[&q.name];
            let (lo, hi) = (
                q.min.unwrap_or(f64::NEG_INFINITY),
                q.max.unwrap_or(f64::INFINITY),
            );
            if !v.is_finite() {
                return Err(invalid(
                    "--set",
                    format!("{}={v}", q.name),
                    "must be a finite number",
                ));
            }
            if v <= lo || v >= hi {
                return Err(invalid(
                    "--set",
                    format!("{}={}", q.name, num(v)),
                    format!(
                        "outside the file's bounds ({}, {}) for {}",
                        num(lo),
                        num(hi),
                        q.name
                    ),
                ));
            }
        }
        Ok(())
    }
    fn sample(
        &self,
        p: &Params,
        rng: &mut ChaCha8Rng,
        frames: usize,
        dt: f64,
        _size: usize,
    ) -> (SampleTruth, Vec<f64>) {
        let (x0, xs) = self.clip(&self.parameter_values(p), rng, frames, dt);
        let truth = SampleTruth::from_pairs(self.file.states.iter().map(|s| s.as_str()).zip(x0));
        let (c, h) = self.map;
        (truth, xs.iter().map(|x| (x - c) / h).collect())
    }
    fn render(&self, _p: &Params, z: &[f64], size: usize, canvas: &mut Canvas, out: &mut [f32]) {
        self.picture.draw(z[0].clamp(-1.0, 1.0), size, canvas, out);
    }
    fn mapping_text(&self) -> &'static str {
        self.mapping
    }
    fn sampling_text(&self) -> &'static str {
        self.sampling
    }
    /// The file's parameters and its derived values.
    fn model_parameters(&self, p: &Params) -> Params {
        let q = self.parameter_values(p);
        let mut out = p.clone();
        for (d, v) in self.file.derived.iter().zip(self.file.derived_values(&q)) {
            out.insert(d.name.clone(), v);
        }
        out
    }
    /// Reference frames of known x (the observed variable), spread over its range.
    fn calibration(&self, _p: &Params, _size: usize, latents: &[Vec<f64>]) -> Calibration {
        let (c, h) = self.map;
        Calibration {
            quantity: Some(format!(
                "the model file's observed variable {}",
                self.file.states[self.file.observed[0]]
            )),
            reference_points: reference_points(latents, |z| c + h * z),
            ..Default::default()
        }
    }
    fn fps(&self, _dt: f64) -> Option<f64> {
        None
    }
    fn released_from_rest(&self) -> bool {
        false
    }
}
