//! `FileBlock`: a model file's system rolled out by the shooting machinery (RK4 with sub-steps
//! through each clip's least-squares initial state), the latent read through an affine map per
//! observed variable: calibrated from reference frames, or learned where the law pins it and
//! held where the law leaves it free.

use super::system::FileSystem;
use crate::physics::block::{BlockOptions, Clips, PhysicsBlock};
use crate::physics::ode::{ObservationMap, ShootingBlock};
use crate::physics::{Bounds, ParamSpec};
use physvid_shared::model_file::symmetry::{transformed, Transform};
use physvid_shared::model_file::ModelFile;
use tch::nn;
use tch::Tensor;

/// Sub-steps per period of the motion at the start (RK4 at 1/40 of a period: a relative phase
/// error of about 3e-5 per period).
const STEPS_PER_PERIOD: f64 = 40.0;
/// Sub-steps per frame when the motion does not oscillate.
const DEFAULT_SUBSTEPS: usize = 4;
/// Most RK4 sub-steps per frame.
const MAX_SUBSTEPS: usize = 200;
/// Levenberg–Marquardt iterations of the final refinement of the parameters.
const REFINE_ITERATIONS: usize = 10;
/// Levenberg–Marquardt iterations of the solve through the smooth map (`ode/smooth.rs`).
const SMOOTH_ITERATIONS: usize = 20;

/// Clips the final scan of time scales looks at.
const SCAN_CLIPS: i64 = 64;
/// Time scales the final scan tries.
const SCAN_POINTS: usize = 24;
/// The scan's range of frequencies: from the frames' Nyquist limit (×0.9) down this factor.
const SCAN_RANGE: f64 = 32.0;

/// The block of a model file.
pub struct FileBlock {
    shooting: ShootingBlock,
    /// Latent coordinates per frame.
    dims: i64,
    file: ModelFile,
    /// The file's system, for the scan (the shooting block owns another copy).
    system: FileSystem,
    dt: f64,
}

impl FileBlock {
    /// `init`: the file's parameters, then the map's scale and offset (one start for every
    /// coordinate); `learn` says which parts of an uncalibrated map are learned.
    pub fn new(
        path: &nn::Path,
        file: &ModelFile,
        system: &FileSystem,
        specs: &[ParamSpec],
        init: &[f64],
        opts: BlockOptions,
        learn: (bool, bool),
    ) -> FileBlock {
        let m = file.parameters.len();
        let d = file.observed.len() as i64;
        let (s, c) = (init[m], init[m + d as usize]);
        let map = if opts.calibrated {
            ObservationMap::new(&(path / "map"), d, s, c, true)
        } else {
            let s = if learn.0 { s } else { 1.0 };
            let c = if learn.1 { c } else { 0.0 };
            ObservationMap::partly_learned(&(path / "map"), d, (s, learn.0), (c, learn.1))
        };
        let substeps = match system.frequency(&init[..m], opts.dt) {
            Some(w) => {
                let period = std::f64::consts::TAU / w;
                ((opts.dt * STEPS_PER_PERIOD / period).ceil() as usize).clamp(2, MAX_SUBSTEPS)
            }
            None => DEFAULT_SUBSTEPS,
        };
        let shooting = ShootingBlock::new(
            path,
            Box::new(system.clone()),
            &specs[..m],
            &init[..m],
            map,
            file.observed.clone(),
            opts.dt,
            substeps,
        );
        FileBlock {
            shooting,
            dims: d,
            file: file.clone(),
            system: system.clone(),
            dt: opts.dt,
        }
    }

    /// The parameters rescaled in time (`model_file::symmetry`) so that the motion's frequency
    /// runs over a log grid up to the frames' Nyquist limit: a global look before the local
    /// refinement (the misfit has a minimum per basin of frequency), where the motion
    /// oscillates.
    fn time_scales(&self) -> Vec<Vec<f64>> {
        let m = self.file.parameters.len();
        let p = self.shooting.values()[..m].to_vec();
        let Some(w) = self.system.frequency(&p, self.dt) else {
            return Vec::new();
        };
        let top = 0.9 * std::f64::consts::PI / self.dt;
        (0..SCAN_POINTS)
            .filter_map(|i| {
                let target = top / SCAN_RANGE.powf(1.0 - i as f64 / (SCAN_POINTS - 1) as f64);
                transformed(
                    &self.file,
                    &self.system.compiled,
                    &p,
                    Transform::Time(target / w),
                )
            })
            .filter(|q| {
                q.iter()
                    .zip(&self.file.parameters)
                    .all(|(v, s)| Bounds::new(s.min, s.max).contains(*v))
            })
            .collect()
    }
}

impl PhysicsBlock for FileBlock {
    fn order(&self) -> i64 {
        2
    }

    fn rollout(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor {
        let z = z.narrow(1, 0, steps);
        let z = if self.dims == 1 { z.unsqueeze(-1) } else { z };
        let out = self.shooting.from_observed(
            &self
                .shooting
                .observed_rollout(&self.shooting.to_observed(&z), clips),
        );
        if self.dims == 1 {
            out.squeeze_dim(-1)
        } else {
            out
        }
    }

    fn values(&self, _latents: &Tensor) -> Vec<f64> {
        self.shooting.values()
    }

    /// The scan of time scales on up to [`SCAN_CLIPS`] clips, then Levenberg–Marquardt.
    fn refine(&self, z: &Tensor, clips: Clips) -> bool {
        let z = if self.dims == 1 {
            z.unsqueeze(-1)
        } else {
            z.shallow_clone()
        };
        let candidates = self.time_scales();
        let n = z.size()[0].min(SCAN_CLIPS);
        let start = clips.start.map(|s| s.narrow(0, 0, n));
        let subset = Clips {
            start: start.as_ref(),
            ids: None,
        };
        let scanned = self.shooting.scan(&z.narrow(0, 0, n), subset, &candidates);
        let refined = self.shooting.refine(&z, clips, REFINE_ITERATIONS);
        self.shooting.refine_smooth(&z, clips, SMOOTH_ITERATIONS) || refined || scanned
    }

    fn calibrate(&self, latents: &Tensor, values: &Tensor) {
        self.shooting.calibrate(latents, values);
    }
    fn law_failure(&self) -> Option<String> {
        self.shooting.law_failure()
    }
}
