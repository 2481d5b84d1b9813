//! Whether curved maps of the observed variable keep a law's form: a first-order law in one
//! observed variable that is affine in it, x' = a(p)·(x − x*(p)), turns under y = |x − x*|^q
//! into y' = q·a·y, the same law with its rate scaled by q. An encoder free to bend its
//! latent then leaves the rate undetermined (Newton's cooling through brightness came out 10 %
//! low); a linear encoder, which cannot bend it, pins it.

use super::system::CompiledSystem;
use super::ModelFile;

/// Whether `file`'s law keeps its form under curved maps of its observed variable: one state,
/// observed, no explicit time, and its right-hand side affine in the state at the starting
/// parameters (checked at sampled states over the `[initial]` range, or [−1, 1]).
pub fn kept_by_curved_maps(file: &ModelFile, sys: &CompiledSystem) -> bool {
    if file.states.len() != 1 || file.observed != [0] {
        return false;
    }
    let p = file.starts();
    let f = |x: f64, t: f64| {
        let mut out = [0.0];
        sys.eval(&[x], &p, t, &mut out, None);
        out[0]
    };
    let (lo, hi) = file.initial[0].unwrap_or((-1.0, 1.0));
    let (lo, hi) = if hi > lo { (lo, hi) } else { (-1.0, 1.0) };
    let xs: Vec<f64> = (0..9).map(|i| lo + (hi - lo) * i as f64 / 8.0).collect();
    let ys: Vec<f64> = xs.iter().map(|&x| f(x, 0.0)).collect();
    let scale = ys.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    if !scale.is_finite() || scale == 0.0 {
        return false;
    }
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * scale;
    let timeless = xs.iter().zip(&ys).all(|(&x, &y)| close(f(x, 1.7), y));
    // Equal steps: an affine function's second differences vanish.
    let affine = ys.windows(3).all(|w| close(w[0] - 2.0 * w[1] + w[2], 0.0));
    timeless && affine
}

#[cfg(test)]
mod tests {
    use super::super::parse_text;
    use super::*;

    fn kept(params: &str, law: &str) -> bool {
        let f = parse_text(&format!(
            "name = \"m\"\n[parameters]\n{params}\n[state]\nx = \"{law}\"\n[observed]\nlatent = [\"x\"]\n[initial]\nx = [0.5, 1.0]\n"
        ))
        .unwrap();
        kept_by_curved_maps(&f, &CompiledSystem::new(&f))
    }

    #[test]
    fn affine_first_order_laws_are_kept_and_curved_ones_are_not() {
        let two = "r = { start = 1.0, positive = true }\nTa = { start = 0.2 }";
        let one = "r = { start = 1.0, positive = true }";
        assert!(kept(two, "-r*(x - Ta)"));
        assert!(kept(one, "-r*x"));
        assert!(!kept(one, "-r*sqrt(x)"));
        assert!(!kept(two, "-r*x^2 + Ta"));
        assert!(!kept(one, "-r*x*(1 + t)"));
    }
}
