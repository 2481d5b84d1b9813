//! Symbolic derivatives of expressions, simplified as they are built.

use super::{Expr, Func, Op};

/// ∂e/∂(variable `v`).
pub fn derivative(e: &Expr, v: usize) -> Expr {
    match e {
        Expr::Num(_) => Expr::Num(0.0),
        Expr::Var(i) => Expr::Num(f64::from(u8::from(*i == v))),
        Expr::Neg(a) => Expr::negate(derivative(a, v)),
        Expr::Bin(op, a, b) => {
            let (a, b) = (a.as_ref(), b.as_ref());
            let (da, db) = (derivative(a, v), derivative(b, v));
            match op {
                Op::Add => Expr::sum(da, db),
                Op::Sub => Expr::difference(da, db),
                Op::Mul => Expr::sum(Expr::product(da, b.clone()), Expr::product(a.clone(), db)),
                // (a'·b − a·b')/b²
                Op::Div => Expr::quotient(
                    Expr::difference(Expr::product(da, b.clone()), Expr::product(a.clone(), db)),
                    Expr::pow(b.clone(), Expr::Num(2.0)),
                ),
                Op::Pow => {
                    // b·a^(b−1)·a' + a^b·ln(a)·b'
                    let first = Expr::product(
                        Expr::product(
                            b.clone(),
                            Expr::pow(a.clone(), Expr::difference(b.clone(), Expr::Num(1.0))),
                        ),
                        da,
                    );
                    if matches!(db, Expr::Num(x) if x == 0.0) {
                        first
                    } else {
                        let second = Expr::product(
                            Expr::product(e.clone(), Expr::call(Func::Ln, vec![a.clone()])),
                            db,
                        );
                        Expr::sum(first, second)
                    }
                }
            }
        }
        Expr::Call(f, args) => {
            let a = &args[0];
            let da = derivative(a, v);
            let outer = match f {
                Func::Sqrt => Expr::quotient(Expr::Num(0.5), e.clone()),
                Func::Exp => e.clone(),
                Func::Ln => Expr::quotient(Expr::Num(1.0), a.clone()),
                Func::Sin => Expr::call(Func::Cos, vec![a.clone()]),
                Func::Cos => Expr::negate(Expr::call(Func::Sin, vec![a.clone()])),
                Func::Tan => Expr::sum(Expr::Num(1.0), Expr::pow(e.clone(), Expr::Num(2.0))),
                Func::Tanh => {
                    Expr::difference(Expr::Num(1.0), Expr::pow(e.clone(), Expr::Num(2.0)))
                }
                Func::Abs => Expr::call(Func::Sign, vec![a.clone()]),
                Func::Sign | Func::Step => Expr::Num(0.0),
                Func::Min | Func::Max => {
                    let b = &args[1];
                    let db = derivative(b, v);
                    // The chosen argument's derivative: min takes a where b − a ≥ 0.
                    let gap = match f {
                        Func::Min => Expr::difference(b.clone(), a.clone()),
                        _ => Expr::difference(a.clone(), b.clone()),
                    };
                    let pick_a = Expr::call(Func::Step, vec![gap]);
                    return Expr::sum(
                        Expr::product(pick_a.clone(), da),
                        Expr::product(Expr::difference(Expr::Num(1.0), pick_a), db),
                    );
                }
            };
            Expr::product(outer, da)
        }
    }
}
