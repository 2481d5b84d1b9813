//! `PhysicsBlock`: the differentiable model of the latent's dynamics that every model builds,
//! with the options blocks are built with (`BlockOptions`, `Integrator`, `RolloutStart`).

use tch::{Kind, Tensor};

/// How a block advances the latent one frame.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    clap::ValueEnum,
    serde::Serialize,
    serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum Integrator {
    /// Exact propagator of the linear ODE (closed form), or RK4 with sub-steps for nonlinear
    /// ones: no discretisation bias at any dt.
    #[default]
    Exact,
    /// The paper's explicit Euler step with a backward-difference velocity (biased at large dt).
    Euler,
}

impl Integrator {
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Exact => "exact",
            Integrator::Euler => "euler",
        }
    }
}

/// Where the oscillator's rollout starts.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Default,
    clap::ValueEnum,
    serde::Serialize,
    serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum RolloutStart {
    /// The state (z0, z1) whose rollout fits the whole clip in least squares: noise in the first
    /// two frames is not carried through the clip.
    #[default]
    Fit,
    /// The first two encoded frames (the paper's): pixel noise there biases the damping high.
    Frames,
}

/// What a block needs to know besides its parameters.
#[derive(Debug, Clone, Copy)]
pub struct BlockOptions {
    pub integrator: Integrator,
    pub dt: f64,
    /// The clips' start times since the release are known (motion from rest).
    pub timed: bool,
    /// Times before the release are on the law's rise toward it (a toss), not at rest.
    pub rising: bool,
    /// Reference frames of known value will be passed to [`PhysicsBlock::calibrate`].
    pub calibrated: bool,
    /// Where the oscillator's rollout starts.
    pub start: RolloutStart,
}

/// What is known about the clips of a batch besides their frames.
#[derive(Debug, Clone, Copy, Default)]
pub struct Clips<'a> {
    /// Each clip's start time since the release (s) \[B\], where the data gives it.
    pub start: Option<&'a Tensor>,
    /// Each clip's index in the data (training clips first), when the batch holds the data's
    /// clips: a block may keep state per clip across epochs (the shooting fit's warm start).
    pub ids: Option<&'a [usize]>,
}

/// A differentiable model of the latent's dynamics with learnable parameters.
pub trait PhysicsBlock {
    /// Frames the rollout starts from (1 for first-order models, 2 for second-order ones).
    fn order(&self) -> i64;
    /// Rolls the latent out over `steps` frames of `z` [B, T] of the batch `clips`.
    fn rollout(&self, z: &Tensor, clips: Clips, steps: i64) -> Tensor;
    /// Current parameter values, in the order of the model's parameters. Values a block solves
    /// in closed form for each batch (the LED's resting latent) are solved over `latents`
    /// [B, T], the encoded validation clips, so the reported value never depends on which batch
    /// ran last.
    fn values(&self, latents: &Tensor) -> Vec<f64>;
    /// Host-side bookkeeping between optimisation steps, called once per epoch and after a
    /// checkpoint is restored (never inside a step): a block may read its parameters here to
    /// choose how the coming steps compute (the oscillator's closed form).
    fn prepare(&self) {}
    /// Blocks that read a physical quantity off the latent during training (the pendulum's
    /// angle) take the map from reference frames of known value: `latents` and `values` \[R\].
    /// Called before every forward pass when the block was built with `calibrated`.
    fn calibrate(&self, _latents: &Tensor, _values: &Tensor) {}
    /// Solves parameters that gradient descent only creeps towards, on the encoded training
    /// latents `z` [N, T] with the encoder held; called once, on the kept checkpoint. Returns
    /// whether any changed.
    fn refine(&self, _z: &Tensor, _clips: Clips) -> bool {
        false
    }
    /// An extra term the block adds to the MSE+KL training loss, if any (the oscillator's
    /// encoder-only forecast).
    fn auxiliary_loss(&self, _z: &Tensor) -> Option<Tensor> {
        None
    }
    /// The ODE residual at the inner frames of `z` [B, T], [B, T − 2], by central differences,
    /// for `--loss residual+floor`; `None` for blocks that do not offer it.
    fn residual(&self, _z: &Tensor) -> Option<Tensor> {
        None
    }
    /// Where the law itself gave no finite value for most clips of the last batch (a model
    /// file's x/0, √−1, exp(1000), ln of a negative latent), said with the expression and the
    /// state: training cannot move such a law's parameters.
    fn law_failure(&self) -> Option<String> {
        None
    }
}

/// Frame index k = 0..steps as a float row vector [1, steps].
pub fn frame_index(steps: i64, z: &Tensor) -> Tensor {
    Tensor::arange(steps, (Kind::Float, z.device())).unsqueeze(0)
}
