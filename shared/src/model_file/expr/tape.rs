//! A `Tape`: many expressions (f and every entry of its Jacobians) compiled together into one
//! list of operations with common subexpressions shared (hash-consing), evaluated in order into
//! a buffer. The symbolic derivatives of a law repeat its subexpressions many times over (the
//! spring's distance appears in every entry); shared, each is computed once per evaluation.
//!
//! The buffer holds the variables, then the constants, then each operation's result, so that
//! reading a variable or a constant is no operation: only arithmetic is dispatched.

mod native;
mod split;

use super::{Expr, Func, Op};
use std::collections::HashMap;

pub use split::Split;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Node {
    /// A constant, by its bits.
    Num(u64),
    Var(usize),
    Neg(usize),
    Bin(Op, usize, usize),
    Call(Func, usize, Option<usize>),
}

/// One operation on buffer slots: its inputs and the slot it writes.
#[derive(Debug, Clone, Copy)]
enum Step {
    Neg(u32, u32),
    /// The four operations of arithmetic each their own step (one dispatch, not two); `Bin`
    /// is left for powers.
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Div(u32, u32, u32),
    Bin(Op, u32, u32, u32),
    Call(Func, u32, u32, u32),
    /// sin and cos of one argument at once (`sin_cos`): a pendulum's law and its derivative
    /// name both.
    SinCos {
        arg: u32,
        sin: u32,
        cos: u32,
    },
}

/// Compiles expressions into a [`Tape`].
#[derive(Default)]
pub struct TapeBuilder {
    nodes: Vec<Node>,
    index: HashMap<Node, usize>,
    outputs: Vec<Option<usize>>,
}

impl TapeBuilder {
    fn node(&mut self, n: Node) -> usize {
        if let Some(&i) = self.index.get(&n) {
            return i;
        }
        self.nodes.push(n);
        self.index.insert(n, self.nodes.len() - 1);
        self.nodes.len() - 1
    }

    fn add(&mut self, e: &Expr) -> usize {
        let n = match e {
            Expr::Num(v) => Node::Num(v.to_bits()),
            Expr::Var(i) => Node::Var(*i),
            Expr::Neg(a) => Node::Neg(self.add(a)),
            Expr::Bin(op, a, b) => {
                let (a, b) = (self.add(a), self.add(b));
                Node::Bin(*op, a, b)
            }
            Expr::Call(f, args) => {
                let a = self.add(&args[0]);
                let b = args.get(1).map(|b| self.add(b));
                Node::Call(*f, a, b)
            }
        };
        self.node(n)
    }

    /// Adds an output (a constant zero is recorded as such and costs nothing).
    pub fn output(&mut self, e: &Expr) {
        let out = (*e != Expr::Num(0.0)).then(|| self.add(e));
        self.outputs.push(out);
    }

    /// Nodes so far: evaluating this prefix ([`Tape::run`]'s `upto`) computes every output
    /// added so far.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether nothing was added.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The tape: every node given its buffer slot, and each sin and cos of the same argument
    /// computed together.
    pub fn finish(self) -> Tape {
        let vars = self
            .nodes
            .iter()
            .filter_map(|n| match n {
                Node::Var(v) => Some(v + 1),
                _ => None,
            })
            .max()
            .unwrap_or(0);
        // Slots: the variables, a zero (the outputs that are none, the second operand of a
        // function of one), the constants, the results.
        let zero = vars as u32;
        let mut constants = vec![0.0];
        let mut slot = vec![0u32; self.nodes.len()];
        for (i, n) in self.nodes.iter().enumerate() {
            match *n {
                Node::Var(v) => slot[i] = v as u32,
                Node::Num(bits) => {
                    slot[i] = (vars + constants.len()) as u32;
                    constants.push(f64::from_bits(bits));
                }
                _ => {}
            }
        }
        let mut next = vars + constants.len();
        for (i, n) in self.nodes.iter().enumerate() {
            if matches!(n, Node::Neg(_) | Node::Bin(..) | Node::Call(..)) {
                slot[i] = next as u32;
                next += 1;
            }
        }
        let mut steps = Vec::new();
        let mut prefix = Vec::with_capacity(self.nodes.len() + 1);
        let mut fused = vec![false; self.nodes.len()];
        for (i, n) in self.nodes.iter().enumerate() {
            prefix.push(steps.len());
            let s = |k: usize| slot[k];
            let step = match *n {
                Node::Num(_) | Node::Var(_) => None,
                _ if fused[i] => None,
                Node::Neg(a) => Some(Step::Neg(s(a), s(i))),
                Node::Bin(op, a, b) => Some(match op {
                    Op::Add => Step::Add(s(a), s(b), s(i)),
                    Op::Sub => Step::Sub(s(a), s(b), s(i)),
                    Op::Mul => Step::Mul(s(a), s(b), s(i)),
                    Op::Div => Step::Div(s(a), s(b), s(i)),
                    Op::Pow => Step::Bin(op, s(a), s(b), s(i)),
                }),
                Node::Call(f @ (Func::Sin | Func::Cos), a, None) => {
                    let partner = if f == Func::Sin { Func::Cos } else { Func::Sin };
                    match self.index.get(&Node::Call(partner, a, None)) {
                        Some(&j) if j > i => {
                            fused[j] = true;
                            let (sin, cos) = if f == Func::Sin { (i, j) } else { (j, i) };
                            Some(Step::SinCos {
                                arg: s(a),
                                sin: s(sin),
                                cos: s(cos),
                            })
                        }
                        _ => Some(Step::Call(f, s(a), zero, s(i))),
                    }
                }
                Node::Call(f, a, b) => Some(Step::Call(f, s(a), b.map_or(zero, s), s(i))),
            };
            steps.extend(step);
        }
        prefix.push(steps.len());
        Tape {
            vars,
            constants,
            steps,
            prefix,
            outputs: self
                .outputs
                .iter()
                .map(|o| o.map_or(zero, |i| slot[i]))
                .collect(),
            len: next,
        }
    }
}

/// Expressions compiled together; see the module's text.
#[derive(Debug, Clone)]
pub struct Tape {
    /// Variables read (the buffer's first slots).
    vars: usize,
    /// A zero, then the constants (the next slots).
    constants: Vec<f64>,
    steps: Vec<Step>,
    /// `prefix[k]`: the steps that compute the builder's first k nodes.
    prefix: Vec<usize>,
    /// Each output's slot.
    outputs: Vec<u32>,
    /// Slots in all.
    len: usize,
}

impl Tape {
    /// Operations on the tape.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Whether it has no operations.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// The operations that compute the builder's first `upto` nodes.
    pub fn steps(&self, upto: usize) -> usize {
        self.prefix[upto]
    }

    /// The buffer [`Tape::run`] needs.
    pub fn buffer_len(&self) -> usize {
        self.len
    }

    /// Evaluates the builder's first `upto` nodes at `vars` into `buf` (at least
    /// [`Tape::buffer_len`] long).
    pub fn run(&self, vars: &[f64], upto: usize, buf: &mut [f64]) {
        buf[..self.vars].copy_from_slice(&vars[..self.vars]);
        self.load_constants(buf);
        self.exec(&self.steps[..self.prefix[upto]], buf);
    }

    /// Writes the constants into their slots of `buf`.
    fn load_constants(&self, buf: &mut [f64]) {
        buf[self.vars..self.vars + self.constants.len()].copy_from_slice(&self.constants);
    }

    /// Runs `steps`, this tape's, on `buf`.
    fn exec(&self, steps: &[Step], buf: &mut [f64]) {
        // Once a run, so that no access below is checked (a small law evaluated millions of
        // times an epoch spends a third of its time on the checks otherwise).
        assert!(buf.len() >= self.len, "a tape's buffer is too short");
        let at = buf.as_mut_ptr();
        // SAFETY: every slot a step of this tape names is below `self.len` (`finish` numbers
        // them so), and `buf` holds at least that many.
        let get = |slot: u32| unsafe { *at.add(slot as usize) };
        let set = |slot: u32, value: f64| unsafe { *at.add(slot as usize) = value };
        for step in steps {
            match *step {
                Step::Neg(a, out) => set(out, -get(a)),
                Step::Add(a, b, out) => set(out, get(a) + get(b)),
                Step::Sub(a, b, out) => set(out, get(a) - get(b)),
                Step::Mul(a, b, out) => set(out, get(a) * get(b)),
                Step::Div(a, b, out) => set(out, get(a) / get(b)),
                Step::Bin(op, a, b, out) => set(out, op.apply(get(a), get(b))),
                Step::Call(f, a, b, out) => set(out, f.apply(get(a), get(b))),
                Step::SinCos { arg, sin, cos } => {
                    let (s, c) = get(arg).sin_cos();
                    set(sin, s);
                    set(cos, c);
                }
            }
        }
    }

    /// Output `k`'s value after [`Tape::run`] covered it.
    pub fn output(&self, k: usize, buf: &[f64]) -> f64 {
        buf[self.outputs[k] as usize]
    }
}
