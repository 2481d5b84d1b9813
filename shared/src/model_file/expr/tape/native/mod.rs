//! A split tape's varying operations compiled to machine code with Cranelift: one function per
//! stopping point, straight-line, that reads the varying variables and the buffer's fixed slots,
//! keeps every intermediate in registers and writes the outputs where the caller wants them. The
//! interpreter (`Tape::exec`) pays a dispatch and a trip through memory per operation and a
//! gather per output, about 20 ns an evaluation of a pendulum's law with its Jacobians inside
//! the RK4 fits; the hand-written law about 4.
//!
//! The same operations in the same order as the interpreter's, each IEEE-exact in both (Cranelift
//! contracts nothing into fused multiply-adds, and every function other than √ and |x| is a call
//! to the interpreter's own Rust), so the two agree to the bit (tested below). Where Cranelift
//! cannot target the host, `compile` answers `None` and the interpreter runs instead.

mod emit;

use super::Step;
use cranelift_codegen::ir::{types, AbiParam};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, Linkage, Module};
use emit::{Body, Calls};
use std::mem::ManuallyDrop;

/// A compiled stopping point: `buf` the split's buffer (read only), `head` the varying
/// variables but the last, `last` the last, `outs` one pointer per output group.
type Entry =
    unsafe extern "C" fn(buf: *const f64, head: *const f64, last: f64, outs: *const *mut f64);

/// The compiled stopping points of one split tape; see the module's text.
pub(super) struct Native {
    module: ManuallyDrop<JITModule>,
    entries: Vec<Entry>,
}

// SAFETY: after `finalize_definitions` the module's code is never written again; the entries are
// functions of their arguments alone, callable from any thread, and the module is touched only
// by `drop`, which runs once, after every holder of the `Arc` around it is gone.
unsafe impl Send for Native {}
unsafe impl Sync for Native {}

impl Drop for Native {
    fn drop(&mut self) {
        // SAFETY: the entries die with `self`; no caller can hold one past this point.
        unsafe { ManuallyDrop::take(&mut self.module).free_memory() }
    }
}

impl std::fmt::Debug for Native {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Native({} entries)", self.entries.len())
    }
}

/// What a split hands to [`compile`].
pub(super) struct Plan<'a> {
    /// The varying operations, in order.
    pub steps: &'a [Step],
    /// `ends[e]`: how many of `steps` stopping point `e` runs.
    pub ends: &'a [usize],
    /// The slot of each varying variable (the last is `last`, the others `head`).
    pub slots: &'a [usize],
    /// Each output's slot.
    pub outputs: &'a [u32],
    /// `groups[e]`: the outputs stopping point `e` writes; group `g` spans
    /// `groups[g - 1]..groups[g]` (from 0 for the first).
    pub groups: &'a [usize],
    /// Slots in the buffer.
    pub len: usize,
}

impl Native {
    /// Calls stopping point `end`.
    ///
    /// # Safety
    /// `buf` holds at least `plan.len` values, `head` at least one fewer than `plan.slots`, and
    /// `outs[g]` at least group `g`'s outputs for every `g ≤ end`.
    #[inline]
    pub(super) unsafe fn call(
        &self,
        end: usize,
        buf: *const f64,
        head: *const f64,
        last: f64,
        outs: *const *mut f64,
    ) {
        // SAFETY: as the caller promises.
        unsafe { (self.entries[end])(buf, head, last, outs) }
    }
}

/// Compiles every stopping point of `plan`, or `None` where Cranelift cannot target this host.
pub(super) fn compile(plan: &Plan) -> Option<Native> {
    let mut flags = settings::builder();
    flags.set("opt_level", "speed").ok()?;
    let isa = cranelift_native::builder()
        .ok()?
        .finish(settings::Flags::new(flags))
        .ok()?;
    let mut module = JITModule::new(JITBuilder::with_isa(isa, default_libcall_names()));
    let mut ids = Vec::new();
    let mut ctx = module.make_context();
    let mut fctx = FunctionBuilderContext::new();
    let ptr = module.target_config().pointer_type();
    for end in 0..plan.ends.len() {
        ctx.func.signature = module.make_signature();
        let params = [ptr, ptr, types::F64, ptr];
        (ctx.func.signature.params).extend(params.map(AbiParam::new));
        let id = module
            .declare_function(&format!("law{end}"), Linkage::Local, &ctx.func.signature)
            .ok()?;
        let mut b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
        let calls = Calls::new(&module, &mut b, ptr);
        Body::new(plan, b, ptr, calls).emit(end);
        module.define_function(id, &mut ctx).ok()?;
        module.clear_context(&mut ctx);
        ids.push(id);
    }
    module.finalize_definitions().ok()?;
    let entries = ids
        .iter()
        .map(|&id| {
            let code = module.get_finalized_function(id);
            // SAFETY: `code` is a finalized function of the signature declared above, which is
            // `Entry`'s in the host's C calling convention (`make_signature`'s default).
            unsafe { std::mem::transmute::<*const u8, Entry>(code) }
        })
        .collect();
    Some(Native {
        module: ManuallyDrop::new(module),
        entries,
    })
}

#[cfg(test)]
mod tests {
    use super::super::super::parse;
    use super::super::{Split, TapeBuilder};
    use proptest::prelude::*;

    /// Every function and operation a file may write, and through the derivatives the internal
    /// ones (sign, step), over x, v, a, b, t with a and b fixed.
    const TEXTS: &[&str] = &[
        "-a*sin(x) - b*v + cos(x)*tan(v/4)",
        "exp(-b*t)*ln(abs(x) + 1) / (v*v + a)",
        "sqrt(abs(a*x)) - tanh(v)*x^3 + abs(v)^2.5",
        "min(x, v) * max(a, t) + abs(x)^(1/3) - b^-2",
    ];

    /// The texts and their derivatives by x and v, split with x, v and t varying.
    fn split() -> Split {
        let vars = |name: &str| ["x", "v", "a", "b", "t"].iter().position(|n| *n == name);
        let exprs: Vec<_> = TEXTS.iter().map(|t| parse(t, &vars).unwrap()).collect();
        let mut builder = TapeBuilder::default();
        exprs.iter().for_each(|e| builder.output(e));
        let f = builder.len();
        for e in &exprs {
            (0..2).for_each(|j| builder.output(&e.derivative(j)));
        }
        let all = builder.len();
        let n = exprs.len();
        Split::new(builder.finish(), &[0, 1, 4], &[(f, n), (all, 3 * n)])
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: 256,
            rng_seed: proptest::test_runner::RngSeed::Fixed(32),
            ..ProptestConfig::default()
        })]
        #[test]
        fn the_compiled_law_agrees_with_the_interpreter_to_the_bit(
            x in -3.0..3.0f64, v in -3.0..3.0f64, t in -1.0..5.0f64,
            a in 0.1..3.0f64, b in -2.0..2.0f64,
        ) {
            let native = split();
            #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
            prop_assert!(native.is_compiled(), "compiled on this host");
            let interpreted = native.clone().interpreted();
            let fixed = [0.0, 0.0, a, b, 0.0];
            let (mut bn, mut bi) = (native.prepare(&fixed), interpreted.prepare(&fixed));
            for end in 0..2 {
                let (mut fn_, mut jn, mut fi, mut ji) = ([f64::NAN; 4], [f64::NAN; 8], [1.0; 4], [1.0; 8]);
                native.eval(end, &[x, v], t, &mut bn, &mut [&mut fn_, &mut jn]);
                interpreted.eval(end, &[x, v], t, &mut bi, &mut [&mut fi, &mut ji]);
                let bits = |s: &[f64]| s.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                prop_assert_eq!(bits(&fn_), bits(&fi));
                if end == 1 {
                    prop_assert_eq!(bits(&jn), bits(&ji));
                }
            }
        }
    }
}
