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
    /// f(x, p, t) into `f` \[n\]; with `jac`, also ∂f/∂x [n×n] and ∂f/∂p [n×m], row-major.
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
    /// The law in its own words, for a message (a model file's); `None`, the default, names
    /// states and parameters by their place.
    fn words(&self) -> Option<&LawWords> {
        None
    }
}

/// A law's states, each one's d/dt as written, and its parameters' names.
#[derive(Debug, Clone, PartialEq)]
pub struct LawWords {
    pub states: Vec<String>,
    pub equations: Vec<String>,
    pub parameters: Vec<String>,
}

/// Where `sys` is not finite at state `x`, parameters `p`, time `t`: the first derivative that
/// is NaN or infinite there, in the law's words, with the state and the parameters.
pub fn not_finite_at(sys: &dyn OdeSystem, x: &[f64], p: &[f64], t: f64) -> Option<String> {
    let mut f = vec![0.0; sys.states()];
    sys.eval(x, p, t, &mut f, None);
    let i = f.iter().position(|v| !v.is_finite())?;
    let num = physvid_shared::cli::approx;
    let named = |names: Option<&Vec<String>>, values: &[f64], letter: &str| -> String {
        values
            .iter()
            .enumerate()
            .map(|(k, v)| match names.and_then(|n| n.get(k)) {
                Some(n) => format!("{n} = {}", num(*v)),
                None => format!("{letter}{k} = {}", num(*v)),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let words = sys.words();
    let law = match words {
        Some(w) => format!("d{}/dt = {}", w.states[i], w.equations[i]),
        None => format!("the derivative of state {i}"),
    };
    Some(format!(
        "{law} is {} at {} (parameters {}; t = {})",
        f[i],
        named(words.map(|w| &w.states), x, "x"),
        named(words.map(|w| &w.parameters), p, "p"),
        num(t)
    ))
}

/// Where a [`FixedLaw`] writes ∂f/∂x [n×n] and, where given, ∂f/∂p [n×m], row-major.
pub type Jacobians<'a> = Option<(&'a mut [f64], Option<&'a mut [f64]>)>;

/// An [`OdeSystem`] at fixed parameters (from [`OdeSystem::at`]).
pub trait FixedLaw {
    /// f(x, t) into `f`, and the Jacobians asked for.
    fn eval(&mut self, x: &[f64], t: f64, f: &mut [f64], jac: Jacobians);
}
