//! A tape's operations split for many evaluations at which some variables keep their values (a
//! law's parameters through one integration): the operations that read only those and the
//! constants run once (`Split::prepare`), the rest on every evaluation (`Split::eval`), which
//! may stop early (f alone, f with ∂f/∂x) where the later outputs are not needed. The rest is
//! compiled to machine code where the host allows (`native/`), interpreted otherwise.

use super::native::{self, Native, Plan};
use super::{Step, Tape};
use std::sync::Arc;

/// The most stopping points a split may have.
const MAX_ENDS: usize = 4;

/// A tape split by what its operations read; see the module's text.
#[derive(Debug, Clone)]
pub struct Split {
    tape: Tape,
    /// The operations reading no varying variable, even indirectly.
    fixed: Vec<Step>,
    /// The others, in the tape's order.
    varying: Vec<Step>,
    /// `ends[i]`: how many of `varying` compute the builder's first `bounds[i]` nodes.
    ends: Vec<usize>,
    /// `groups[i]`: the outputs the builder's first `bounds[i]` nodes compute.
    groups: Vec<usize>,
    /// The slot of each varying variable: its own where the tape reads it, else one past the
    /// tape's slots (a slot [`Split::prepare`]'s buffer holds and no operation reads).
    slots: Vec<usize>,
    /// `varying` compiled, one function per stopping point (none where the host cannot).
    native: Option<Arc<Native>>,
}

impl Step {
    /// The slots it reads.
    fn reads(&self) -> [u32; 2] {
        match *self {
            Step::Neg(a, _) => [a, a],
            Step::Add(a, b, _)
            | Step::Sub(a, b, _)
            | Step::Mul(a, b, _)
            | Step::Div(a, b, _)
            | Step::Bin(_, a, b, _)
            | Step::Call(_, a, b, _) => [a, b],
            Step::SinCos { arg, .. } => [arg, arg],
        }
    }

    /// The slots it writes.
    fn writes(&self) -> [u32; 2] {
        match *self {
            Step::Neg(_, out)
            | Step::Add(_, _, out)
            | Step::Sub(_, _, out)
            | Step::Mul(_, _, out)
            | Step::Div(_, _, out)
            | Step::Bin(_, _, _, out)
            | Step::Call(_, _, _, out) => [out, out],
            Step::SinCos { sin, cos, .. } => [sin, cos],
        }
    }
}

impl Split {
    /// Splits `tape` for evaluations at which only the variables `varying` (at least one)
    /// change; `bounds` are the stopping points of [`Split::eval`]: node counts
    /// ([`Tape::run`]'s `upto`) and the outputs those nodes compute, both increasing.
    pub fn new(tape: Tape, varying: &[usize], bounds: &[(usize, usize)]) -> Split {
        assert!(!varying.is_empty() && bounds.len() <= MAX_ENDS);
        let mut moves = vec![false; tape.len + 1];
        let slots: Vec<usize> = varying
            .iter()
            .map(|&v| if v < tape.vars { v } else { tape.len })
            .collect();
        for &s in &slots {
            moves[s] = true;
        }
        let (mut fixed, mut var) = (Vec::new(), Vec::new());
        // counts[k]: the varying operations among the tape's first k.
        let mut counts = vec![0];
        for step in &tape.steps {
            if step.reads().iter().any(|&s| moves[s as usize]) {
                for w in step.writes() {
                    moves[w as usize] = true;
                }
                var.push(*step);
            } else {
                fixed.push(*step);
            }
            counts.push(var.len());
        }
        let ends: Vec<usize> = bounds
            .iter()
            .map(|&(b, _)| counts[tape.prefix[b]])
            .collect();
        let groups: Vec<usize> = bounds.iter().map(|&(_, g)| g).collect();
        let native = native::compile(&Plan {
            steps: &var,
            ends: &ends,
            slots: &slots,
            outputs: &tape.outputs,
            groups: &groups,
            len: tape.len + 1,
        });
        Split {
            tape,
            fixed,
            varying: var,
            ends,
            groups,
            slots,
            native: native.map(Arc::new),
        }
    }

    /// Whether the varying operations run as machine code (else interpreted).
    pub fn is_compiled(&self) -> bool {
        self.native.is_some()
    }

    /// The same split, always interpreted (for comparisons).
    #[cfg(test)]
    pub(crate) fn interpreted(mut self) -> Split {
        self.native = None;
        self
    }

    /// The whole tape.
    pub fn tape(&self) -> &Tape {
        &self.tape
    }

    /// A buffer holding the variables `vars` (the varying ones are not read), the constants and
    /// the result of every operation that reads no varying variable.
    pub fn prepare(&self, vars: &[f64]) -> Vec<f64> {
        let mut buf = vec![0.0; self.tape.len + 1];
        buf[..self.tape.vars].copy_from_slice(&vars[..self.tape.vars]);
        self.tape.load_constants(&mut buf);
        self.tape.exec(&self.fixed, &mut buf);
        buf
    }

    /// The outputs of stopping point `end` (`bounds[end]` of [`Split::new`]) at the varying
    /// variables `head` then `last` (in `new`'s order), from a buffer of [`Split::prepare`]:
    /// `outs[g]` receives the outputs of group `g` (those between stopping points g − 1 and g),
    /// for every g up to `end`.
    #[inline]
    pub fn eval(
        &self,
        end: usize,
        head: &[f64],
        last: f64,
        buf: &mut [f64],
        outs: &mut [&mut [f64]],
    ) {
        let groups = &self.groups[..=end];
        assert!(outs.len() >= groups.len(), "an output group is missing");
        let Some(native) = &self.native else {
            return self.interpret(end, (head, last), buf, outs);
        };
        assert!(
            buf.len() > self.tape.len && head.len() + 1 >= self.slots.len(),
            "a split tape's buffer or varying variables are too short"
        );
        let mut ptrs = [std::ptr::null_mut(); MAX_ENDS];
        let mut from = 0;
        for ((ptr, out), &to) in ptrs.iter_mut().zip(outs.iter_mut()).zip(groups) {
            assert!(out.len() >= to - from, "an output group is too short");
            *ptr = out.as_mut_ptr();
            from = to;
        }
        // SAFETY: checked above: the buffer holds every slot, `head` every varying variable but
        // the last, and each group's pointer at least its outputs.
        unsafe { native.call(end, buf.as_ptr(), head.as_ptr(), last, ptrs.as_ptr()) }
    }

    /// [`Split::eval`] on a host the code could not be compiled for (kept out of line, so that
    /// the compiled path inlines into its callers).
    #[inline(never)]
    fn interpret(&self, end: usize, at: (&[f64], f64), buf: &mut [f64], outs: &mut [&mut [f64]]) {
        let (&last_slot, heads) = self.slots.split_last().expect("a varying variable");
        for (&s, &v) in heads.iter().zip(at.0) {
            buf[s] = v;
        }
        buf[last_slot] = at.1;
        self.tape.exec(&self.varying[..self.ends[end]], buf);
        let mut from = 0;
        for (out, &to) in outs.iter_mut().zip(&self.groups[..=end]) {
            self.outputs(from, buf, &mut out[..to - from]);
            from = to;
        }
    }

    /// Outputs `from`, `from` + 1, … into `out`, after [`Split::interpret`] computed them.
    fn outputs(&self, from: usize, buf: &[f64], out: &mut [f64]) {
        for (o, &s) in out.iter_mut().zip(&self.tape.outputs[from..]) {
            *o = buf[s as usize];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::parse;
    use super::super::TapeBuilder;
    use super::*;

    #[test]
    fn a_split_tape_gives_the_whole_tapes_outputs_to_the_bit_and_runs_less() {
        // Variables x, v, a, b, t; a and b fixed.
        let vars = |name: &str| ["x", "v", "a", "b", "t"].iter().position(|n| *n == name);
        let texts = [
            "-a*sin(x) - b*v",
            "exp(-b*t)*cos(x) + a*a/b",
            "sqrt(a + b) * v - a*b",
        ];
        let mut builder = TapeBuilder::default();
        builder.output(&parse(texts[0], &vars).unwrap());
        let first = builder.len();
        for t in &texts[1..] {
            builder.output(&parse(t, &vars).unwrap());
        }
        let all = builder.len();
        let tape = builder.finish();
        let split = Split::new(tape.clone(), &[0, 1, 4], &[(first, 1), (all, 3)]);
        assert!(split.varying.len() < tape.len() && split.ends[0] < split.ends[1]);
        #[cfg(any(target_arch = "x86_64", target_arch = "aarch64"))]
        assert!(split.is_compiled(), "compiled on this host");
        let fixed = [0.0, 0.0, 1.7, 0.3, 0.0];
        for split in [split.clone(), split.interpreted()] {
            let mut buf = split.prepare(&fixed);
            for (x, v, t) in [(0.4, -1.1, 0.0), (-2.0, 0.5, 3.25), (1.0, 0.0, -0.5)] {
                let at = [x, v, fixed[2], fixed[3], t];
                let mut whole = vec![f64::NAN; tape.buffer_len()];
                tape.run(&at, all, &mut whole);
                let (mut f, mut rest) = ([f64::NAN; 1], [f64::NAN; 2]);
                split.eval(0, &[x, v], t, &mut buf, &mut [&mut f]);
                assert_eq!(f[0].to_bits(), tape.output(0, &whole).to_bits());
                split.eval(1, &[x, v], t, &mut buf, &mut [&mut f, &mut rest]);
                for (k, got) in f.iter().chain(&rest).enumerate() {
                    let want = tape.output(k, &whole);
                    assert_eq!(got.to_bits(), want.to_bits(), "{} at {at:?}", texts[k]);
                }
            }
        }
    }
}
