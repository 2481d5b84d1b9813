//! Something beside a falling object where it starts: the hand that held it opening beside
//! it, or pulled back. What is measured on those frames spreads further than on the rest of
//! the descent, and the positions (and the release read from them) are pulled with it
//! (`Descent::crowded`, judged by `verdict::release`).

/// The early part of a descent, as a share of the way: where the release is read.
pub const EARLY: f64 = 0.3;

/// How much further than on the rest of the descent what is measured may spread on an early
/// frame before the frame counts as crowded.
const CROWDED: f64 = 1.3;

/// The share of a descent's early frames (its first [`EARLY`] of the way, up to frame `last`
/// of `path`) where what is measured spreads over [`CROWDED`] times as far as on the later
/// frames (`spread`, per frame): something else differs beside the object where it starts.
pub fn crowded(path: &[(usize, f64)], spread: &[f64], last: usize) -> f64 {
    let (early, mut later) = parts(path, spread, last);
    if early.is_empty() || later.is_empty() {
        return 0.0;
    }
    later.sort_by(f64::total_cmp);
    share_over(&early, later[later.len() / 2])
}

/// As [`crowded`], against the spread `usual` (of the object alone: at rest, before anything
/// beside it moves).
pub fn crowded_against(path: &[(usize, f64)], spread: &[f64], last: usize, usual: f64) -> f64 {
    share_over(&parts(path, spread, last).0, usual)
}

/// The spreads of the early frames of `path` up to `last`, and of the later ones.
fn parts(path: &[(usize, f64)], spread: &[f64], last: usize) -> (Vec<f64>, Vec<f64>) {
    let out: Vec<(usize, f64)> = path.iter().copied().filter(|q| q.0 <= last).collect();
    let (Some(&(_, from)), Some(&(_, to))) = (out.first(), out.last()) else {
        return (Vec::new(), Vec::new());
    };
    let (early, later): (Vec<_>, Vec<_>) = out
        .iter()
        .map(|&(k, p)| (p - from <= EARLY * (to - from), spread[k]))
        .partition(|q| q.0);
    let only = |v: Vec<(bool, f64)>| v.into_iter().map(|q| q.1).collect();
    (only(early), only(later))
}

/// The share of `early` over [`CROWDED`] times `usual`.
fn share_over(early: &[f64], usual: f64) -> f64 {
    if early.is_empty() {
        return 0.0;
    }
    early.iter().filter(|&&s| s > CROWDED * usual).count() as f64 / early.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn early_frames_measured_wide_are_crowded() {
        // 40 frames of a descent; the first 30 % of the way is frames 0–21 (p = k²).
        let path: Vec<(usize, f64)> = (0..40).map(|k| (k, (k * k) as f64)).collect();
        let mut spread = vec![2.0; 40];
        assert_eq!(crowded(&path, &spread, 39), 0.0);
        // Something beside the object on its first 11 frames: half of the 22 early ones.
        for s in &mut spread[..11] {
            *s = 3.0;
        }
        assert!((crowded(&path, &spread, 39) - 0.5).abs() < 1e-9);
        // Only later frames: not where the release is read.
        let mut late = vec![2.0; 40];
        for s in &mut late[30..] {
            *s = 5.0;
        }
        assert_eq!(crowded(&path, &late, 39), 0.0);
    }

    #[test]
    fn early_frames_are_judged_against_the_spread_given() {
        let path: Vec<(usize, f64)> = (0..40).map(|k| (k, (k * k) as f64)).collect();
        let mut spread = vec![2.0; 40];
        for s in &mut spread[..11] {
            *s = 3.0;
        }
        // The object alone spreads 2.5 (at rest): 3 is not 1.3 times as far; against 2, it is.
        assert_eq!(crowded_against(&path, &spread, 39, 2.5), 0.0);
        assert!((crowded_against(&path, &spread, 39, 2.0) - 0.5).abs() < 1e-9);
    }
}
