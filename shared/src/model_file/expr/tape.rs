//! A `Tape`: many expressions (f and every entry of its Jacobians) compiled together into one
//! list of operations with common subexpressions shared (hash-consing), evaluated in order into
//! a buffer. The symbolic derivatives of a law repeat its subexpressions many times over (the
//! spring's distance appears in every entry); shared, each is computed once per evaluation.

use super::{Expr, Func, Op};
use std::collections::HashMap;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Node {
    /// A constant, by its bits.
    Num(u64),
    Var(usize),
    Neg(usize),
    Bin(Op, usize, usize),
    Call(Func, usize, Option<usize>),
    /// sin and cos of one argument at once (`sin_cos`), the sine here and the cosine into the
    /// slot of the later node, which becomes [`Node::Done`] (made by [`TapeBuilder::finish`]).
    SinCos {
        arg: usize,
        sin_here: bool,
        other: usize,
    },
    /// Computed by an earlier node.
    Done,
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

    /// Operations so far: evaluating this many computes every output added so far.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether nothing was added.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The tape, with each sin and cos of the same argument computed together (a pendulum's
    /// law and its derivative name both).
    pub fn finish(mut self) -> Tape {
        for i in 0..self.nodes.len() {
            let Node::Call(f @ (Func::Sin | Func::Cos), arg, None) = self.nodes[i] else {
                continue;
            };
            let partner = if f == Func::Sin { Func::Cos } else { Func::Sin };
            if let Some(&j) = self.index.get(&Node::Call(partner, arg, None)) {
                if j > i {
                    let sin_here = f == Func::Sin;
                    self.nodes[i] = Node::SinCos {
                        arg,
                        sin_here,
                        other: j,
                    };
                    self.nodes[j] = Node::Done;
                }
            }
        }
        Tape {
            nodes: self.nodes,
            outputs: self.outputs,
        }
    }
}

/// Expressions compiled together; see the module's text.
#[derive(Debug, Clone)]
pub struct Tape {
    nodes: Vec<Node>,
    outputs: Vec<Option<usize>>,
}

impl Tape {
    /// Operations on the tape.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether it has no operations.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Evaluates the first `upto` operations at `vars` into `buf` (as long as the tape: a fused
    /// sin and cos may write past `upto`).
    pub fn run(&self, vars: &[f64], upto: usize, buf: &mut [f64]) {
        for (i, n) in self.nodes[..upto].iter().enumerate() {
            buf[i] = match *n {
                Node::Num(bits) => f64::from_bits(bits),
                Node::Var(v) => vars[v],
                Node::Neg(a) => -buf[a],
                Node::Bin(op, a, b) => op.apply(buf[a], buf[b]),
                Node::Call(f, a, b) => f.apply(buf[a], b.map_or(0.0, |b| buf[b])),
                Node::SinCos {
                    arg,
                    sin_here,
                    other,
                } => {
                    let (sin, cos) = buf[arg].sin_cos();
                    let (here, there) = if sin_here { (sin, cos) } else { (cos, sin) };
                    buf[other] = there;
                    here
                }
                Node::Done => buf[i],
            };
        }
    }

    /// Output `k`'s value after [`Tape::run`] covered it.
    pub fn output(&self, k: usize, buf: &[f64]) -> f64 {
        self.outputs[k].map_or(0.0, |i| buf[i])
    }
}
