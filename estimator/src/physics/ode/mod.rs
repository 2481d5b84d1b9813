//! The machinery every RK4-integrated model shares (the pendulum, the spring, models from a
//! file): an `OdeSystem` (dx/dt = f(x, p, t) with its Jacobians) is integrated in plain Rust
//! on f64 together with its exact sensitivities (`rk4.rs`), each clip's initial state is
//! fitted to the encoded latents by Levenberg–Marquardt (`shooting.rs`), and `ShootingBlock`
//! (`block.rs`) hands the result back to autograd as a first-order surrogate: a few tensor
//! operations whose value is the fitted trajectory and whose gradients are its sensitivities.
//! Hundreds of tiny tensor operations per batch become one pass over f64 arrays.

pub mod block;
pub mod map;
mod refine;
pub mod rk4;
pub mod shooting;
mod smooth;

pub use block::ShootingBlock;
pub use map::ObservationMap;

/// dx/dt = f(x, p, t) with learnable parameters p.
pub trait OdeSystem: Send + Sync {
    /// State dimension n.
    fn states(&self) -> usize;
    /// Parameter count m (the block's physics parameters, in their order).
    fn params(&self) -> usize;
    /// f(x, p, t) into `f` [n]; with `jac`, also ∂f/∂x [n×n] and ∂f/∂p [n×m], row-major.
    fn eval(
        &self,
        x: &[f64],
        p: &[f64],
        t: f64,
        f: &mut [f64],
        jac: Option<(&mut [f64], &mut [f64])>,
    );
    /// A first guess of the initial state from the observed values `obs` [frames × observed,
    /// row-major] of state components `observed`, `dt` apart (for example a velocity from
    /// finite differences).
    fn guess(&self, obs: &[f64], observed: &[usize], dt: f64) -> Vec<f64>;
    /// The law at fixed parameters `p` for the many evaluations of one integration, where
    /// computing what depends on `p` alone once pays (a model file's tape); `None`, the
    /// default, integrates through [`OdeSystem::eval`].
    fn at<'a>(&'a self, _p: &[f64]) -> Option<Box<dyn FixedLaw + 'a>> {
        None
    }
}

/// Where a [`FixedLaw`] writes ∂f/∂x [n×n] and, where given, ∂f/∂p [n×m], row-major.
pub type Jacobians<'a> = Option<(&'a mut [f64], Option<&'a mut [f64]>)>;

/// An [`OdeSystem`] at fixed parameters (from [`OdeSystem::at`]).
pub trait FixedLaw {
    /// f(x, t) into `f`, and the Jacobians asked for.
    fn eval(&mut self, x: &[f64], t: f64, f: &mut [f64], jac: Jacobians);
}
