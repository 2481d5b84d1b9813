//! `Program`: one expression compiled into postfix steps over a fixed stack (its depth bounds
//! how deeply a file may nest), evaluated without allocating.

use super::{Expr, Func, Op};

/// One step of a compiled expression.
#[derive(Debug, Clone, Copy)]
pub(super) enum Step {
    Num(f64),
    Var(usize),
    Neg,
    Bin(Op),
    Call(Func),
}

/// A compiled expression: postfix steps over a stack of at most [`MAX_DEPTH`] values.
#[derive(Debug, Clone)]
pub struct Program {
    pub(super) ops: Vec<Step>,
    /// The deepest the stack gets.
    pub depth: usize,
}

/// The deepest stack a program may need (the model file's validation refuses deeper nesting).
pub const MAX_DEPTH: usize = 64;

impl Program {
    pub(super) fn emit(&mut self, e: &Expr, depth: &mut usize) {
        let push = |p: &mut Program, depth: &mut usize| {
            *depth += 1;
            p.depth = p.depth.max(*depth);
        };
        match e {
            Expr::Num(v) => {
                self.ops.push(Step::Num(*v));
                push(self, depth);
            }
            Expr::Var(i) => {
                self.ops.push(Step::Var(*i));
                push(self, depth);
            }
            Expr::Neg(a) => {
                self.emit(a, depth);
                self.ops.push(Step::Neg);
            }
            Expr::Bin(op, a, b) => {
                self.emit(a, depth);
                self.emit(b, depth);
                self.ops.push(Step::Bin(*op));
                *depth -= 1;
            }
            Expr::Call(f, args) => {
                for a in args {
                    self.emit(a, depth);
                }
                if args.len() == 2 {
                    *depth -= 1;
                }
                self.ops.push(Step::Call(*f));
            }
        }
    }

    /// The value at variables `vars`.
    pub fn eval(&self, vars: &[f64]) -> f64 {
        let mut stack = [0.0f64; MAX_DEPTH];
        let mut top = 0usize;
        for op in &self.ops {
            match *op {
                Step::Num(v) => {
                    stack[top] = v;
                    top += 1;
                }
                Step::Var(i) => {
                    stack[top] = vars[i];
                    top += 1;
                }
                Step::Neg => stack[top - 1] = -stack[top - 1],
                Step::Bin(op) => {
                    top -= 1;
                    stack[top - 1] = op.apply(stack[top - 1], stack[top]);
                }
                Step::Call(f) => {
                    if f.arity() == 2 {
                        top -= 1;
                        stack[top - 1] = f.apply(stack[top - 1], stack[top]);
                    } else {
                        stack[top - 1] = f.apply(stack[top - 1], 0.0);
                    }
                }
            }
        }
        stack[0]
    }

    /// A constant program's value (`None` when it reads a variable).
    pub fn constant(&self) -> Option<f64> {
        match self.ops[..] {
            [Step::Num(v)] => Some(v),
            _ => None,
        }
    }
}
