//! `Network`: the encoder and the physics block with their variable stores, the forward pass
//! (encode clips, roll the latent out), and the reference frames a calibrating block reads
//! its map from. Training, the timeline and the report all go through `forward`.

use crate::config::RunConfig;
use crate::data::ClipData;
use crate::encoder::{centroid, Encoder};
use crate::loss::LossKind;
use crate::physics::{BlockOptions, Clips, ModelRef, PhysicsBlock};
use tch::nn;
use tch::{Device, Kind, Tensor};

/// Frames of known physical value that a calibrated block reads its map from during training.
struct ReferenceFrames {
    /// [1, R, D], standardised like the clips.
    frames: Tensor,
    /// [R].
    values: Tensor,
}

impl ReferenceFrames {
    /// The reference frames of `reference` (clip, frame, value) for a block that calibrates
    /// during training (the pendulum), when two or more distinct values are given.
    fn for_training(
        model: ModelRef,
        data: &ClipData,
        reference: &[(usize, usize, f64)],
    ) -> Option<Self> {
        let distinct = reference.iter().any(|r| r.2 != reference[0].2);
        if !model.calibrates_in_training() || reference.len() < 2 || !distinct {
            return None;
        }
        let frames: Vec<Tensor> = reference
            .iter()
            .map(|&(clip, frame, _)| {
                let (x, i) = data.clip(clip);
                x.get(i).get(frame as i64)
            })
            .collect();
        let values: Vec<f32> = reference.iter().map(|r| r.2 as f32).collect();
        Some(ReferenceFrames {
            frames: Tensor::stack(&frames, 0).unsqueeze(0),
            values: Tensor::from_slice(&values).to_device(data.train.device()),
        })
    }
}

/// Encoder and physics block with their variable stores.
pub struct Network {
    enc_vs: nn::VarStore,
    phys_vs: nn::VarStore,
    pub encoder: Encoder,
    block: Box<dyn PhysicsBlock>,
    reference: Option<ReferenceFrames>,
    /// The model the block is of, and its frame interval (the configuration's).
    pub model: ModelRef,
    pub dt: f64,
}

impl Network {
    /// Builds the network with weights seeded by `cfg.seed` and physics parameters at `init`.
    pub fn new(cfg: &RunConfig, data: &ClipData, device: Device, init: &[f64]) -> Network {
        let reference = ReferenceFrames::for_training(cfg.model, data, &cfg.calibration.reference);
        tch::manual_seed(cfg.seed as i64);
        let enc_vs = nn::VarStore::new(device);
        let phys_vs = nn::VarStore::new(device);
        let [_, _, c, h, w] = data.shape.map(|v| v as i64);
        let encoder = Encoder::new(
            &(enc_vs.root() / "encoder"),
            (c, h, w),
            cfg.encoder,
            cfg.model.latent_dims() as i64,
            &data.train,
            centroid::Where {
                line: data.line(),
                located: data.object_located(),
                background: &data.background,
            },
        );
        let block = cfg.model.build(
            &(phys_vs.root() / "physics"),
            init,
            BlockOptions {
                integrator: cfg.integrator,
                dt: cfg.dt,
                timed: data.train_start.is_some(),
                rising: data.rising,
                calibrated: reference.is_some(),
                start: cfg.rollout_start,
            },
        );
        let network = Network {
            enc_vs,
            phys_vs,
            encoder,
            block,
            reference,
            model: cfg.model,
            dt: cfg.dt,
        };
        network.prepare();
        network
    }

    /// The block's once-per-epoch bookkeeping (see [`PhysicsBlock::prepare`]).
    pub fn prepare(&self) {
        self.block.prepare();
    }

    /// Where the block's law gave no finite value for most clips of a batch, if it did.
    pub fn law_failure(&self) -> Option<String> {
        self.block.law_failure()
    }

    /// The encoder's and the block's variable stores (for their optimisers).
    /// Frames each clip's rollout starts from: the states fitted per clip.
    pub fn start_frames(&self) -> i64 {
        self.block.order()
    }

    pub fn stores(&self) -> (&nn::VarStore, &nn::VarStore) {
        (&self.enc_vs, &self.phys_vs)
    }

    /// Encodes clips `x` [B, T, D] and rolls the latent out: (encoded, rolled out) [B, T] each.
    pub fn forward(&self, x: &Tensor, clips: Clips, steps: i64) -> (Tensor, Tensor) {
        self.forward_input(&self.encoder.input(x), clips, steps)
    }

    /// As [`Network::forward`], from what [`Encoder::input`] made of the clips.
    pub fn forward_input(&self, i: &Tensor, clips: Clips, steps: i64) -> (Tensor, Tensor) {
        self.calibrate();
        let z = self.encoder.encode_input(i);
        let z_hat = self.block.rollout(&z, clips, steps);
        (z, z_hat)
    }

    /// The block's rollout of held latents `z` over `steps` frames, without recalibrating the
    /// map from the reference frames (the verdict's refits move the block's variables one by
    /// one and must see each move).
    pub fn rollout_held(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor {
        self.block.rollout(z, clips, steps)
    }

    /// The block's own final refinement on held latents, without recalibrating the map first;
    /// false when the block has none (or it changed nothing).
    pub fn refine_held(&self, z: &Tensor, clips: Clips) -> bool {
        self.block.refine(z, clips)
    }

    /// The block's trainable variables (maps calibrated from references excluded), sorted by
    /// name.
    pub fn physics_variables(&self) -> Vec<Tensor> {
        let mut named: Vec<(String, Tensor)> = self
            .phys_vs
            .variables()
            .into_iter()
            .filter(|(_, t)| t.requires_grad())
            .collect();
        named.sort_by(|a, b| a.0.cmp(&b.0));
        named.into_iter().map(|(_, t)| t).collect()
    }

    /// The block's ODE residual of `z` when the loss needs it.
    pub fn residual(&self, kind: LossKind, z: &Tensor) -> Option<Tensor> {
        (kind == LossKind::ResidualFloor)
            .then(|| self.block.residual(z))
            .flatten()
    }

    /// The block's final refinement on latents `z` (see [`PhysicsBlock::refine`]), the map
    /// calibrated again on the held encoder's latents of the reference frames first.
    pub fn refine(&self, z: &Tensor, clips: Clips) -> bool {
        self.calibrate();
        self.block.refine(z, clips)
    }

    /// Fits the block's map to the reference frames' latents under the current encoder.
    fn calibrate(&self) {
        if let Some(r) = &self.reference {
            let z_ref = tch::no_grad(|| self.encoder.encode(&r.frames));
            self.block.calibrate(&z_ref, &r.values);
        }
    }

    /// The block's extra loss term for latents `z`, if any.
    pub fn auxiliary_loss(&self, z: &Tensor) -> Option<Tensor> {
        self.block.auxiliary_loss(z)
    }

    /// The block's parameter values, those solved per batch solved over `latents` [B, T].
    pub fn values(&self, latents: &Tensor) -> Vec<f64> {
        self.block.values(latents)
    }

    /// Every variable of the encoder and the block, in a fixed order (sorted by name).
    fn variables(&self) -> Vec<Tensor> {
        let mut out = Vec::new();
        for vs in [&self.enc_vs, &self.phys_vs] {
            let mut vars: Vec<_> = vs.variables().into_iter().collect();
            vars.sort_by(|a, b| a.0.cmp(&b.0));
            out.extend(vars.into_iter().map(|(_, t)| t));
        }
        out
    }

    /// A copy of every variable.
    pub fn snapshot(&self) -> Vec<Tensor> {
        self.variables().iter().map(|t| t.detach().copy()).collect()
    }

    /// Puts back a [`Network::snapshot`].
    pub fn restore(&self, saved: &[Tensor]) {
        tch::no_grad(|| {
            for (mut t, s) in self.variables().into_iter().zip(saved) {
                t.copy_(s);
            }
        });
        self.prepare();
    }
}

/// A [B, T] (or [B, T, D]) tensor as rows of f32 on the host (T·D values each, frame-major).
pub fn to_rows(t: &Tensor) -> Vec<Vec<f32>> {
    let b = t.size()[0];
    let t = t
        .to_device(Device::Cpu)
        .to_kind(Kind::Float)
        .contiguous()
        .view([b, -1]);
    let (rows, cols) = t.size2().expect("a matrix");
    let flat = Vec::<f32>::try_from(&t.view([-1])).expect("float tensor");
    (0..rows as usize)
        .map(|r| flat[r * cols as usize..(r + 1) * cols as usize].to_vec())
        .collect()
}
