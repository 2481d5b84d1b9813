//! A tape's operations split for many evaluations at which some variables keep their values (a
//! law's parameters through one integration): the operations that read only those and the
//! constants run once (`Split::prepare`), the rest on every evaluation (`Split::run`), which
//! may stop early (f alone, f with ∂f/∂x) where the later outputs are not needed.

use super::{Step, Tape};

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
    /// The slot of each varying variable: its own where the tape reads it, else one past the
    /// tape's slots (a slot [`Split::prepare`]'s buffer holds and no operation reads).
    slots: Vec<usize>,
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
    /// Splits `tape` for evaluations at which only the variables `varying` change; `bounds` are
    /// node counts ([`Tape::run`]'s `upto`) at which [`Split::run`] may stop.
    pub fn new(tape: Tape, varying: &[usize], bounds: &[usize]) -> Split {
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
        let ends = bounds.iter().map(|&b| counts[tape.prefix[b]]).collect();
        Split {
            tape,
            fixed,
            varying: var,
            ends,
            slots,
        }
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

    /// Sets the varying variables to `values` (in `new`'s order) in a buffer from
    /// [`Split::prepare`] and evaluates the builder's first `bounds[end]` nodes.
    #[inline]
    pub fn run(&self, end: usize, values: impl IntoIterator<Item = f64>, buf: &mut [f64]) {
        for (&s, v) in self.slots.iter().zip(values) {
            buf[s] = v;
        }
        self.tape.exec(&self.varying[..self.ends[end]], buf);
    }

    /// Outputs `from`, `from` + 1, … into `out`, after [`Split::run`] covered them.
    #[inline]
    pub fn outputs(&self, from: usize, buf: &[f64], out: &mut [f64]) {
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
        let split = Split::new(tape.clone(), &[0, 1, 4], &[first, all]);
        assert!(split.varying.len() < tape.len() && split.ends[0] < split.ends[1]);
        let fixed = [0.0, 0.0, 1.7, 0.3, 0.0];
        let mut buf = split.prepare(&fixed);
        for (x, v, t) in [(0.4, -1.1, 0.0), (-2.0, 0.5, 3.25), (1.0, 0.0, -0.5)] {
            let at = [x, v, fixed[2], fixed[3], t];
            let mut whole = vec![f64::NAN; tape.buffer_len()];
            tape.run(&at, all, &mut whole);
            let mut got = [f64::NAN; 3];
            split.run(0, [x, v, t], &mut buf);
            split.outputs(0, &buf, &mut got[..1]);
            assert_eq!(got[0].to_bits(), tape.output(0, &whole).to_bits());
            split.run(1, [x, v, t], &mut buf);
            split.outputs(0, &buf, &mut got);
            for (k, got) in got.iter().enumerate() {
                let want = tape.output(k, &whole);
                assert_eq!(got.to_bits(), want.to_bits(), "{} at {at:?}", texts[k]);
            }
        }
    }
}
