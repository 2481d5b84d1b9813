//! The object located by matching its picture (normalised cross-correlation of a template),
//! where its difference from the background does not locate it (`data::object`): a brass mass
//! on a stretching spring, whose coils and paper card differ from the background as much as
//! the mass does and take the difference's peak in turn. A template cut from one frame around
//! the object is found in every frame where the picture matches it best; what it follows is
//! the object's appearance, not where the picture differs most.
//!
//! Measured on the shared m515 spring (59×95 pixels, the 143 frames after the hand): the
//! difference's centroid jumps (second differences 1.46× the first), the matched path is
//! smooth and a damped sinusoid leaves 0.05 % of its height unexplained.

use tch::{Kind, Tensor};

/// Matches are sought only where some frame differs from the median frame at least this share
/// as much as where one differs most (over the template's area): a metre stick or a pole the
/// template resembles, which never moves, never takes the match; the ends of a swing, where
/// the object spends little time, stay in reach (the frames' spread there is small, and the
/// match had jumped at them).
const MOVING: f64 = 0.25;

/// A template of the object and where it may be found.
#[derive(Debug)]
pub struct Template {
    /// The template [1, 1, th, tw], zero mean and unit norm.
    patch: Tensor,
    /// Where its top-left corner may lie [H − th + 1, W − tw + 1] (1: the frames vary there).
    allowed: Tensor,
    /// Height and width of a frame.
    frame: (i64, i64),
    /// The least contrast (root sum of squares about the mean) a patch of the frame must have
    /// to be matched: a tenth of the template's. In a plain wall both the correlation and the
    /// contrast are rounding errors, and their ratio had taken the match.
    contrast: f64,
}

impl Template {
    /// The template for frames `x` [F, C·H·W] of `frame` = (C, H, W) as decoded (or any
    /// positive affine map of them: normalised cross-correlation ignores it): cut from the frame
    /// that differs most from the median frame, around where it differs most, as large as
    /// what differs there. `None` when nothing differs.
    pub fn new(x: &Tensor, frame: (i64, i64, i64)) -> Option<Template> {
        tch::no_grad(|| {
            let (_, h, w) = frame;
            let v = grey(x, frame);
            let f = v.size()[0];
            if f < 2 {
                return None;
            }
            let d = (&v - v.median_dim(0, true).0).abs();
            let r = d
                .sum_dim_intlist([1, 2].as_slice(), false, Kind::Float)
                .argmax(0, false);
            let at = d.index_select(0, &r.view([1])).view([1, 1, h, w]);
            let map = at.avg_pool2d([3, 3], [1, 1], [1, 1], false, true, None::<i64>);
            let peak = map.max().double_value(&[]);
            if peak <= 0.0 {
                return None;
            }
            let area = map.ge(0.5 * peak).sum(Kind::Float).double_value(&[]);
            let radius = ((area / std::f64::consts::PI).sqrt().ceil() as i64)
                .clamp(2, (h.min(w) / 4).max(2));
            let side = (2 * radius + 1).min(h).min(w);
            let idx = map.view([-1]).argmax(0, false).int64_value(&[]);
            let (cy, cx) = (idx / w, idx % w);
            let y0 = (cy - radius).clamp(0, h - side);
            let x0 = (cx - radius).clamp(0, w - side);
            let patch = v
                .index_select(0, &r.view([1]))
                .narrow(1, y0, side)
                .narrow(2, x0, side);
            let patch = &patch - patch.mean(Kind::Float);
            let norm = patch.square().sum(Kind::Float).sqrt().double_value(&[]);
            if norm <= 1e-9 {
                return None;
            }
            let reach = d.amax(0, false).view([1, 1, h, w]);
            let spread = box_mean(&reach, side);
            let top = spread.max().double_value(&[]);
            Some(Template {
                patch: (patch / norm).view([1, 1, side, side]),
                allowed: spread.ge(MOVING * top).to_kind(Kind::Float).squeeze(),
                frame: (h, w),
                contrast: 0.1 * norm,
            })
        })
    }

    /// Each frame's match (x, y) [F, 2] of frames `x` [F, C·H·W] as [`Template::new`] read
    /// them: the template's centre where it matches best, to a fraction of a pixel (a parabola
    /// through the match and its neighbours), in units of half the larger side from the
    /// frame's centre (as `centroid::positions`).
    pub fn positions(&self, x: &Tensor, frame: (i64, i64, i64)) -> Tensor {
        let (h, w) = self.frame;
        let side = self.patch.size()[2];
        let v = grey(x, frame).unsqueeze(1);
        let f = v.size()[0];
        let n = (side * side) as f64;
        let dot = v.conv2d(&self.patch, None::<Tensor>, [1, 1], [0, 0], [1, 1], 1);
        let mean = box_mean(&v, side);
        let var = (box_mean(&v.square(), side) - mean.square()).clamp_min(0.0) * n;
        let spread = var.sqrt();
        let allowed = spread.ge(self.contrast).to_kind(Kind::Float) * &self.allowed;
        let score = dot / spread.clamp_min(self.contrast);
        let (hc, wc) = (h - side + 1, w - side + 1);
        let allowed = allowed.view([f, hc, wc]);
        let score = score.view([f, hc, wc]) * &allowed + (&allowed - 1.0) * 4.0;
        let s: Vec<f32> =
            Vec::try_from(score.reshape([-1]).to_device(tch::Device::Cpu)).unwrap_or_default();
        let cell = 2.0 / h.max(w) as f64;
        let half = (side - 1) as f64 / 2.0;
        let per = (hc * wc) as usize;
        let out: Vec<f32> = s
            .chunks(per.max(1))
            .flat_map(|c| {
                let (i, j) = best(c, wc as usize);
                let at = |a: usize, b: usize| f64::from(c[a * wc as usize + b]);
                let dy = refine(i, hc as usize, |k| at(k, j));
                let dx = refine(j, wc as usize, |k| at(i, k));
                let px = j as f64 + dx + half + 0.5 - w as f64 / 2.0;
                let py = i as f64 + dy + half + 0.5 - h as f64 / 2.0;
                [(px * cell) as f32, (py * cell) as f32]
            })
            .collect();
        Tensor::from_slice(&out).view([-1, 2]).to_device(x.device())
    }
}

/// The mean of every `side`×`side` square of `t` [N, 1, H, W] (no padding), as a column's
/// mean then a row's: the same mean as one square pooling, at 2·side additions an output
/// instead of side² (the square pooling took half of a hand-held spring's run).
fn box_mean(t: &Tensor, side: i64) -> Tensor {
    t.avg_pool2d([side, 1], [1, 1], [0, 0], false, true, None::<i64>)
        .avg_pool2d([1, side], [1, 1], [0, 0], false, true, None::<i64>)
}

/// A template as the centroid encoder's front end uses it on standardised clips: the mean
/// training frame added back to each frame (the mean frame subtracted leaves the object's ghost
/// where it hangs most, and the match jumps to it), and the mean match on the training frames
/// taken off (as the centroid's own window takes off the frame's: a mass swinging low in its
/// frame otherwise starts the head's latent far from the law's rest, which its bias did not
/// reach in 300 steps on the m515 spring).
#[derive(Debug)]
pub struct Matched {
    template: Template,
    background: Tensor,
    mean: Tensor,
}

impl Matched {
    /// The template of standardised training frames `train` [F, C·H·W] of `frame`, whose
    /// mean frame in their units is `background` [C·H·W]; `None` when nothing differs.
    pub fn new(train: &Tensor, background: &Tensor, frame: (i64, i64, i64)) -> Option<Matched> {
        let background = background.view([1, -1]);
        let decoded = train + &background;
        let template = Template::new(&decoded, frame)?;
        let mean = tch::no_grad(|| {
            template
                .positions(&decoded, frame)
                .mean_dim(0, true, Kind::Float)
        });
        Some(Matched {
            template,
            background,
            mean,
        })
    }

    /// Each standardised frame's match [F, 2] less the training frames' mean match.
    pub fn positions(&self, x: &Tensor, frame: (i64, i64, i64)) -> Tensor {
        self.template.positions(&(x + &self.background), frame) - &self.mean
    }
}

/// Frames [F, C·H·W] as their channels' sum [F, H, W].
fn grey(x: &Tensor, (c, h, w): (i64, i64, i64)) -> Tensor {
    let f = x.size()[0];
    x.view([f, c, h, w]).sum_dim_intlist(1, false, Kind::Float)
}

/// The row and column of the largest score of a map `c` `wc` wide.
fn best(c: &[f32], wc: usize) -> (usize, usize) {
    let k = c
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(k, _)| k);
    (k / wc, k % wc)
}

/// The offset (within ±½) of a peak at `i` of `n` values `at(k)` from the parabola through it and
/// its neighbours; 0 at an edge or where they do not bend down.
fn refine(i: usize, n: usize, at: impl Fn(usize) -> f64) -> f64 {
    if i == 0 || i + 1 >= n {
        return 0.0;
    }
    let (a, b, c) = (at(i - 1), at(i), at(i + 1));
    let bend = a - 2.0 * b + c;
    if bend >= 0.0 {
        return 0.0;
    }
    (0.5 * (a - c) / bend).clamp(-0.5, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames [F, H·W] of a light wall with a dark 3×6 bar at `rows` (fractional), column 10,
    /// and a static dark stripe of the same shape at column 2 (it never moves).
    fn frames(rows: &[f64], h: i64, w: i64) -> Tensor {
        let v = super::super::drawn(rows, h, w, |r| {
            vec![[r, r + 6.0, 10.0, 13.0], [20.0, 26.0, 2.0, 5.0]]
        });
        Tensor::from_slice(&v).view([rows.len() as i64, h * w])
    }

    /// The bar's top row in 40 frames of a swing of ±15 px about row 25.
    fn swing() -> Vec<f64> {
        (0..40)
            .map(|k| 25.0 + 15.0 * (0.4 * k as f64).sin())
            .collect()
    }

    #[test]
    fn the_match_follows_the_moving_bar_to_a_fraction_of_a_pixel_and_never_the_pole() {
        let (h, w) = (60, 16);
        let rows = swing();
        let x = frames(&rows, h, w);
        let t = Template::new(&x, (1, h, w)).expect("a template");
        let p = t.positions(&x, (1, h, w));
        // Units of half of 60 px: 30 px per unit from the centre; the bar's centre is r + 3,
        // the template's a fixed offset from it (cut where the difference peaked).
        let y = |k: usize| p.double_value(&[k as i64, 1]) * 30.0 + 30.0;
        let x = |k: usize| p.double_value(&[k as i64, 0]) * 30.0 + 8.0;
        let offset = y(0) - (rows[0] + 3.0);
        assert!(
            offset.abs() < 3.0,
            "the template lies off the bar: {offset}"
        );
        assert!(
            (x(0) - 11.5).abs() < 3.0,
            "the template lies off the bar: x {}",
            x(0)
        );
        for (k, &r) in rows.iter().enumerate() {
            let off = y(k) - (r + 3.0);
            assert!(
                (off - offset).abs() < 0.3,
                "frame {k}: {} for {}",
                y(k),
                r + 3.0
            );
            assert!((x(k) - x(0)).abs() < 0.3, "frame {k}: x {}", x(k));
        }
    }

    #[test]
    fn frames_that_never_change_give_no_template() {
        let x = frames(&[30.0; 10], 60, 16);
        assert!(Template::new(&x, (1, 60, 16)).is_none());
    }

    #[test]
    fn on_standardised_clips_the_match_is_the_bars_row_less_its_mean() {
        let (h, w) = (60, 16);
        let rows = swing();
        let x = frames(&rows, h, w);
        // Standardised as the clips are: the mean frame off, divided by one spread.
        let mean = x.mean_dim(0, false, Kind::Float);
        let spread = (&x - &mean).square().mean(Kind::Float).sqrt();
        let clips = (&x - &mean) / &spread;
        let m = Matched::new(&clips, &(&mean / &spread), (1, h, w)).expect("a template");
        let p = m.positions(&clips, (1, h, w));
        // The matched rows less their mean are the bar's less theirs, to a fraction of a pixel.
        let centre = rows.iter().sum::<f64>() / rows.len() as f64;
        for (k, &r) in rows.iter().enumerate() {
            let y = p.double_value(&[k as i64, 1]) * 30.0;
            assert!(
                (y - (r - centre)).abs() < 0.3,
                "frame {k}: {y} for {}",
                r - centre
            );
        }
    }
}
