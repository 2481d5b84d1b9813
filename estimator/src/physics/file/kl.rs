//! A model file's expressions as tensor operations: what the KL term holds near N(0, 1) when the
//! file names combinations of the observed variables (`[observed] kl`, the spring's relative
//! position), computed from the latent with gradients reaching the encoder.

use physvid_shared::model_file::expr::{Expr, Func, Op};
use tch::{Kind, Tensor};

/// `e` with variable `i` read by `var(i)` (tensors of one shape).
pub fn tensor(e: &Expr, var: &dyn Fn(usize) -> Tensor) -> Tensor {
    match e {
        Expr::Num(v) => Tensor::from(*v as f32),
        Expr::Var(i) => var(*i),
        Expr::Neg(a) => -tensor(a, var),
        Expr::Bin(op, a, b) => {
            let (a, b) = (tensor(a, var), tensor(b, var));
            match op {
                Op::Add => a + b,
                Op::Sub => a - b,
                Op::Mul => a * b,
                Op::Div => a / b,
                Op::Pow => a.pow(&b),
            }
        }
        Expr::Call(f, args) => {
            let a = tensor(&args[0], var);
            match f {
                Func::Sqrt => a.sqrt(),
                Func::Exp => a.exp(),
                Func::Ln => a.log(),
                Func::Sin => a.sin(),
                Func::Cos => a.cos(),
                Func::Tan => a.tan(),
                Func::Tanh => a.tanh(),
                Func::Abs => a.abs(),
                Func::Sign => a.sign(),
                Func::Step => a.ge(0.0).to_kind(Kind::Float),
                Func::Min => a.minimum(&tensor(&args[1], var)),
                Func::Max => a.maximum(&tensor(&args[1], var)),
            }
        }
    }
}

/// The KL coordinates [B, T, K] of latents `z` [B, T, D] whose coordinate k observes state
/// `observed[k]`.
pub fn kl_coordinates(kl: &[Expr], observed: &[usize], z: &Tensor) -> Tensor {
    let var = |i: usize| {
        let k = observed
            .iter()
            .position(|&o| o == i)
            .expect("kl reads observed variables");
        z.select(-1, k as i64)
    };
    // Each reads an observed variable (the file's reader refuses constants), so each is [B, T].
    let parts: Vec<Tensor> = kl.iter().map(|e| tensor(e, &var)).collect();
    Tensor::stack(&parts, -1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use physvid_shared::model_file::expr::parse;

    #[test]
    fn tensor_expressions_match_their_f64_values() {
        let vars = |n: &str| ["a", "b"].iter().position(|x| *x == n);
        let at = [0.7f64, -1.3];
        for text in [
            "b - a",
            "sqrt(a^2 + b^2) * 2",
            "max(a, b) - min(a, b) + abs(b) + exp(a)/tanh(2)",
            "-a^2",
        ] {
            let e = parse(text, &vars).unwrap();
            let t = tensor(&e, &|i| Tensor::from(at[i] as f32)).double_value(&[]);
            assert!((t - e.eval(&at)).abs() < 1e-5, "{text}: {t}");
        }
        let z = Tensor::from_slice(&[1.0f32, 2.0, 4.0, 7.0]).view([1, 1, 4]);
        let rel = parse("x2 - x1", &|n| {
            ["x1", "y1", "x2", "y2"].iter().position(|x| *x == n)
        })
        .unwrap();
        let k = kl_coordinates(&[rel], &[0, 1, 2, 3], &z);
        assert_eq!(k.size(), [1, 1, 1]);
        assert_eq!(k.double_value(&[0, 0, 0]), 3.0);
    }
}
