//! The centroid encoder for one object crossing the frame (a ball falling past a wall, a block
//! sliding down an incline): where the frame differs most from the mean training frame, the
//! centroid of that difference within a window around it, and a learned affine map of the
//! centroid's (x, y) to the latent.
//!
//! Why: a fall or a slide visits each position once, so the validation clips (the recording's
//! end) show the object where no training frame did; an MLP on pixels has no weights there that
//! training fixed (measured on the shared ball: its latent zigzags over the last fifth, and g
//! spreads from 3 to 20 m/s² over seeds). A centroid is affine in the object's position
//! wherever it is, so the law's fit tests the footage rather than the encoder's interpolation.
//! The window keeps the rest of the frame (compression flicker, exposure steps) out of it.

use super::blur::smoothed;
use super::keypoints::centres;
use super::template::Matched;
use serde::Serialize;
use tch::nn;
use tch::{Kind, Tensor};

/// The locating softmax's sharpness per standardised unit: an object 10 units above the
/// background outweighs 10⁴ background pixels by e²⁰.
const SHARPNESS: f64 = 2.0;

/// The centroid encoder's fixed front end: frames to the object's (x, y). It has no weights,
/// so training computes it once per frame (`Encoder::input`) and learns only the affine head.
#[derive(Debug)]
pub struct Front {
    /// Channels, height and width of a frame (channels are summed).
    frame: (i64, i64, i64),
    /// +1 when the object is brighter than the mean frame, −1 when darker.
    polarity: f64,
    /// The window's standard deviation (pixels).
    window: f64,
    /// A descent's line: the position along it, a, read as a/(1 + bend·a) (its bend by
    /// perspective undone, `data::perspective`), and nothing across it (a fall's sideways
    /// wobble gave every training seed its own mix of the two: g spread 2.5 % over seeds).
    line: Option<Line>,
    /// How the object is located in each frame.
    located: Located,
    /// For [`Located::Matched`]: the template and what it matches on.
    matched: Option<Matched>,
}

/// What a recording says of where its object is, for the front end (`data::ClipData`).
#[derive(Debug, Clone, Copy)]
pub struct Where<'a> {
    /// A descent's line (`data::descent`).
    pub line: Option<Line>,
    /// How the object was found (`data::object`).
    pub located: Located,
    /// The mean training frame [C·H·W] in the clips' standardised units.
    pub background: &'a Tensor,
}

/// How the object is located in each frame (`data::object` tries them in this order).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Located {
    /// Where the frame differs most from the background, and measured there.
    #[default]
    Frames,
    /// As `Frames` on the frames blurred (a thin rod's ghost outweighs a faint bob pixel for
    /// pixel but not blob for blob), and measured on the frames themselves.
    Blurred,
    /// Where a template of the object matches best (`template`): its picture, not where the
    /// frame differs most.
    Matched,
}

/// The line of a descent (`data::descent`) along which the front end reads positions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Line {
    /// The path's direction (x, y), a unit vector.
    pub axis: [f64; 2],
    /// κ in a/(1 + κ·a), a the position along `axis` in the front end's units (0: no bend).
    pub bend: f64,
}

impl Front {
    /// The front end for frames of `frame` = (C, H, W), the window sized on the standardised
    /// training frames `train` [.., C·H·W] (smoothed first where the object is located
    /// blurred), reading the object where `at` says (the template of a `Matched` object is
    /// cut from the training frames with the background added back).
    pub fn new(frame: (i64, i64, i64), train: &Tensor, at: Where) -> Front {
        let Where {
            line,
            located,
            background,
        } = at;
        let train = train.reshape([-1, frame.0 * frame.1 * frame.2]);
        let matched = (located == Located::Matched)
            .then(|| Matched::new(&train, background, frame))
            .flatten();
        let map = if located == Located::Blurred {
            smoothed(&train, frame)
        } else {
            train.shallow_clone()
        };
        let polarity = super::keypoints::polarity(&map);
        let window = window(&map, frame, polarity);
        Front {
            frame,
            polarity,
            window,
            line,
            located,
            matched,
        }
    }

    /// Frames [F, C·H·W] → positions [F, 2] (on a descent's line: the position along it with
    /// the bend undone, and a zero).
    pub fn positions(&self, x: &Tensor) -> Tensor {
        let p = if let Some(m) = &self.matched {
            m.positions(x, self.frame)
        } else if self.located == Located::Blurred {
            let by = smoothed(x, self.frame);
            positions_on(&by, x, self.frame, self.polarity, self.window)
        } else {
            positions(x, self.frame, self.polarity, self.window)
        };
        let Some(line) = self.line else {
            return p;
        };
        let axis = Tensor::from_slice(&line.axis.map(|v| v as f32))
            .to_device(p.device())
            .view([2, 1]);
        let a = p.matmul(&axis);
        let a = &a / (&a * line.bend + 1.0);
        // The head keeps its two inputs (nothing across the line), so that it starts as for
        // any centroid: one input changes its initial weights and, on the 60-fps tilted fall
        // of `descent_cli`, g by 1 % (+0.9 % → +2.0 %).
        Tensor::cat(&[&a, &a.zeros_like()], 1)
    }
}

/// The encoder's learned part: an affine map of the position (x, y) to `dims` numbers.
pub fn head(path: &nn::Path, dims: i64) -> nn::Linear {
    nn::linear(path / "head", 2, dims, Default::default())
}

/// Signed difference [F, H, W] of frames `x` [F, C·H·W] in the object's direction.
fn signed(x: &Tensor, (c, h, w): (i64, i64, i64), polarity: f64) -> Tensor {
    let f = x.size()[0];
    x.view([f, c, h, w]).sum_dim_intlist(1, false, Kind::Float) * polarity
}

/// The window's width: twice the object's radius (the median over training frames of the
/// number of pixels above half the frame's peak, taken as a disc), at least 2 pixels.
pub(crate) fn window(train: &Tensor, frame: (i64, i64, i64), polarity: f64) -> f64 {
    tch::no_grad(|| {
        let v = signed(
            &train.reshape([-1, frame.0 * frame.1 * frame.2]),
            frame,
            polarity,
        );
        let f = v.size()[0];
        let flat = v.view([f, -1]);
        let peak = flat.amax(1, true);
        let area = flat
            .ge_tensor(&(&peak * 0.5))
            .to_kind(Kind::Float)
            .sum_dim_intlist(1, false, Kind::Float);
        let median = area.median().double_value(&[]);
        (2.0 * (median / std::f64::consts::PI).sqrt()).max(2.0)
    })
}

/// Frames `x` [F, H·W] as their difference from the median frame (the background, where a
/// moving object spends under half its time), standardised, with the polarity of what differs
/// and the window that measures it.
pub(crate) fn from_background(x: &Tensor, frame: (i64, i64, i64)) -> (Tensor, f64, f64) {
    let d = x - x.median_dim(0, true).0;
    let d = &d / d.square().mean(Kind::Float).sqrt().clamp_min(1e-9);
    let polarity = super::keypoints::polarity(&d);
    let window = window(&d, frame, polarity);
    (d, polarity, window)
}

/// Each frame's object position (x, y) [F, 2] in units of half the larger side, from the
/// centre: a sharp softmax finds the object, the centroid of the positive difference within a
/// Gaussian window there says where it is to a fraction of a pixel.
pub fn positions(x: &Tensor, frame: (i64, i64, i64), polarity: f64, window: f64) -> Tensor {
    let v = signed(x, frame, polarity);
    Windowed::new(&v, &v, window).centre()
}

/// As [`positions`] on frames `d` [F, C·H·W], with the polarity and the window read off them
/// blurred, and the object located there (`smoothed`).
pub fn positions_smoothed(d: &Tensor, frame: (i64, i64, i64)) -> Tensor {
    let by = smoothed(d, frame);
    let polarity = super::keypoints::polarity(&by);
    let window = window(&by, frame, polarity);
    positions_on(&by, d, frame, polarity, window)
}

/// As [`positions`], the object found where `by` [F, C·H·W] (the frames [`smoothed`]) is
/// largest in its direction and measured on `x`.
fn positions_on(
    by: &Tensor,
    x: &Tensor,
    frame: (i64, i64, i64),
    polarity: f64,
    window: f64,
) -> Tensor {
    Windowed::new(
        &signed(by, frame, polarity),
        &signed(x, frame, polarity),
        window,
    )
    .centre()
}

/// As [`positions`], the object found where `by` [F, C·H·W] is largest in its direction (a
/// difference from an earlier frame: what moves) and measured on `x`; with how far what was
/// measured spreads about its centroid \[F\] (the object's own size, or more where something
/// else differs beside it).
pub fn located(
    by: &Tensor,
    x: &Tensor,
    frame: (i64, i64, i64),
    polarity: f64,
    window: f64,
) -> (Tensor, Tensor) {
    let m = Windowed::new(
        &signed(by, frame, polarity),
        &signed(x, frame, polarity),
        window,
    );
    let centre = m.centre();
    let spread = m.spread(&centre);
    (centre, spread)
}

/// What is measured of each frame: the positive signed difference within a Gaussian window
/// around the object, as its column and row sums, with the pixels' centres.
struct Windowed {
    /// Column sums [F, W] and row sums [F, H] of the windowed mass, and its total [F].
    columns: Tensor,
    rows: Tensor,
    total: Tensor,
    xs: Tensor,
    ys: Tensor,
}

impl Windowed {
    /// The object found where the signed differences `by` [F, H, W] peak, measured on the
    /// signed differences `v` [F, H, W] within a window of `window` pixels.
    fn new(by: &Tensor, v: &Tensor, window: f64) -> Windowed {
        let (f, h, w) = v.size3().expect("signed differences are [F, H, W]");
        let side = h.max(w);
        let cell = 2.0 / side as f64;
        let (xs, ys) = (centres(w, cell, v), centres(h, cell, v));
        let locate = (by.view([f, h * w]) * SHARPNESS)
            .softmax(1, Kind::Float)
            .view([f, h, w]);
        let cx = (locate.sum_dim_intlist(1, false, Kind::Float) * &xs).sum_dim_intlist(
            1,
            true,
            Kind::Float,
        );
        let cy = (locate.sum_dim_intlist(2, false, Kind::Float) * &ys).sum_dim_intlist(
            1,
            true,
            Kind::Float,
        );
        let sigma = window * 2.0 / side as f64;
        let gx = ((xs.unsqueeze(0) - cx) / sigma).square() * -0.5;
        let gy = ((ys.unsqueeze(0) - cy) / sigma).square() * -0.5;
        let gauss = gy.exp().unsqueeze(2) * gx.exp().unsqueeze(1);
        let mass = v.relu() * gauss;
        Windowed {
            total: mass.sum_dim_intlist([1, 2].as_slice(), false, Kind::Float) + 1e-6,
            columns: mass.sum_dim_intlist(1, false, Kind::Float),
            rows: mass.sum_dim_intlist(2, false, Kind::Float),
            xs,
            ys,
        }
    }

    /// The mass's centroid (x, y) [F, 2].
    fn centre(&self) -> Tensor {
        let along = |sums: &Tensor, at: &Tensor| {
            (sums * at).sum_dim_intlist(1, false, Kind::Float) / &self.total
        };
        Tensor::stack(
            &[along(&self.columns, &self.xs), along(&self.rows, &self.ys)],
            -1,
        )
    }

    /// The rms distance [F] of the mass from `centre` [F, 2].
    fn spread(&self, centre: &Tensor) -> Tensor {
        let moment = |sums: &Tensor, at: &Tensor, c: i64| {
            let d = (at.unsqueeze(0) - centre.select(1, c).unsqueeze(1)).square();
            (sums * d).sum_dim_intlist(1, false, Kind::Float)
        };
        ((moment(&self.columns, &self.xs, 0) + moment(&self.rows, &self.ys, 1)) / &self.total)
            .sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames [F, H·W] of a dark 3×3 square on a light wall at rows `rows`, column 4.
    fn frames(rows: &[f64], h: i64, w: i64) -> Tensor {
        let v = super::super::drawn(rows, h, w, |r| vec![[r, r + 3.0, 3.0, 6.0]]);
        let t = Tensor::from_slice(&v).view([rows.len() as i64, h * w]);
        let mean = t.mean_dim(0, true, Kind::Float);
        let d = &t - &mean;
        let std = d.square().mean(Kind::Float).sqrt();
        d / std
    }

    #[test]
    fn the_position_is_affine_in_the_objects_row_to_a_fraction_of_a_pixel() {
        let (h, w) = (60, 10);
        let rows: Vec<f64> = (0..40).map(|k| 5.0 + 1.23 * k as f64).collect();
        let x = frames(&rows, h, w);
        let pol = super::super::keypoints::polarity(&x);
        assert_eq!(pol, -1.0);
        let win = window(&x, (1, h, w), pol);
        let p = positions(&x, (1, h, w), pol, win);
        // y in units of half of 60 px: 30 px per unit; the square's centre is row r + 1.5.
        for (k, &r) in rows.iter().enumerate() {
            let y = p.double_value(&[k as i64, 1]) * 30.0 + 30.0;
            assert!(
                (y - (r + 1.5)).abs() < 0.05,
                "frame {k}: {y} for {}",
                r + 1.5
            );
            let x = p.double_value(&[k as i64, 0]) * 30.0 + 5.0;
            assert!((x - 4.5).abs() < 0.05, "frame {k}: x {x}");
        }
    }
}
