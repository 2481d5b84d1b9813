//! The object followed by its colour: where what differs from the background beside a falling
//! object where it starts is something else (the hand that held it, opening), the grey
//! difference measures both and pulls the release (`crowd`); the object's own colour, read
//! where it is clear of the rest, tells it apart from a hand of another colour
//! (`tinted::in_colour` reads the release again from these positions).

/// Object and background chromaticities closer than this (in r, g, b shares of the
/// brightness) are not told apart by colour: a grey object on a grey wall, a red ball before
/// a red door.
pub const MIN_SEPARATION: f64 = 0.06;

/// Pixels darker than this (the mean of r, g, b in [0, 1]) have no colour to read.
const DARK: f32 = 0.04;

/// Colour frames [F, 3, H, W] (`colour_frames`), frame `first` of the grey decode first, at
/// `scale` colour pixels per grey pixel of a grey frame `grey` = (W, H).
pub struct Hue<'a> {
    pub frames: &'a [f32],
    pub first: usize,
    pub scale: usize,
    pub grey: (usize, usize),
}

/// Where the object is on one frame, by its colour: (frame, [x, y] in grey pixels from the
/// frame's centre, as the centroid encoder reads them; how far what was measured spreads
/// about it, in grey pixels).
pub type Followed = (usize, [f64; 2], f64);

impl Hue<'_> {
    fn size(&self) -> (usize, usize) {
        (self.grey.0 * self.scale, self.grey.1 * self.scale)
    }

    fn frames_held(&self) -> usize {
        let (w, h) = self.size();
        self.frames.len() / (3 * w * h)
    }

    /// The colour (r, g, b) of pixel (i, j) of frame `k` (of the grey decode).
    fn rgb(&self, k: usize, i: usize, j: usize) -> [f32; 3] {
        let (w, h) = self.size();
        let at = (k - self.first) * 3 * w * h + j * w + i;
        [
            self.frames[at],
            self.frames[at + w * h],
            self.frames[at + 2 * w * h],
        ]
    }

    /// A grey position (pixels from the centre) in colour pixels, and back.
    fn to_colour(&self, p: [f64; 2]) -> [f64; 2] {
        let f = self.scale as f64;
        [
            (p[0] + self.grey.0 as f64 / 2.0) * f - 0.5,
            (p[1] + self.grey.1 as f64 / 2.0) * f - 0.5,
        ]
    }
    fn to_grey(&self, c: [f64; 2]) -> [f64; 2] {
        let f = self.scale as f64;
        [
            (c[0] + 0.5) / f - self.grey.0 as f64 / 2.0,
            (c[1] + 0.5) / f - self.grey.1 as f64 / 2.0,
        ]
    }

    /// The pixels within `r` of colour position `c`, clipped to the frame.
    fn around(&self, c: [f64; 2], r: f64) -> impl Iterator<Item = (usize, usize)> {
        let (w, h) = self.size();
        let span = |v: f64, n: usize| {
            let lo = (v - r).floor().max(0.0) as usize;
            let hi = ((v + r).ceil().max(0.0) as usize).min(n.saturating_sub(1));
            lo..=hi
        };
        let (xs, ys) = (span(c[0], w), span(c[1], h));
        ys.flat_map(move |j| xs.clone().map(move |i| (i, j)))
    }

    /// The object on frames `guide` (frame, grey position: where the grey difference put it),
    /// by its colour: its colour read on frame `clean` (where it is alone, at `guide`'s
    /// position there) against frame `away` (where it is elsewhere). `None` where its colour
    /// is not told apart from the background's there ([`MIN_SEPARATION`]).
    pub fn follow(
        &self,
        guide: &[(usize, [f64; 2])],
        clean: usize,
        away: usize,
    ) -> Option<Vec<Followed>> {
        let held = self.first..self.first + self.frames_held();
        if !held.contains(&clean) || !held.contains(&away) {
            return None;
        }
        let at_clean = guide.iter().find(|g| g.0 == clean)?.1;
        let (w, h) = self.size();
        let centre = self.to_colour(at_clean);
        // The object on the clean frame: the pixels that differ most from the frame where it
        // is elsewhere, near where the grey difference put it.
        let search = (0.04 * w.max(h) as f64).max(6.0);
        let differ: Vec<((usize, usize), f32)> = self
            .around(centre, search)
            .map(|(i, j)| {
                let (a, b) = (self.rgb(clean, i, j), self.rgb(away, i, j));
                ((i, j), (0..3).map(|c| (a[c] - b[c]).abs()).sum::<f32>())
            })
            .collect();
        let most = differ.iter().map(|d| d.1).fold(0.0f32, f32::max);
        if most <= 0.0 {
            return None;
        }
        let object: Vec<(usize, usize)> = differ
            .iter()
            .filter(|d| d.1 >= 0.5 * most)
            .map(|d| d.0)
            .collect();
        // Its colour: its pixels' that differ most in colour from the background there (a
        // moving object's edge is blurred with the wall behind it).
        let background = mean(object.iter().map(|&(i, j)| chroma(self.rgb(away, i, j))))?;
        let mut own: Vec<([f64; 3], f64)> = object
            .iter()
            .map(|&(i, j)| {
                let c = chroma(self.rgb(clean, i, j));
                (c, distance(c, background))
            })
            .collect();
        own.sort_by(|a, b| b.1.total_cmp(&a.1));
        let colour = mean(own.iter().take(own.len().div_ceil(4)).map(|c| c.0))?;
        let separation = distance(colour, background);
        if separation < MIN_SEPARATION {
            return None;
        }
        let radius = (object.len() as f64 / std::f64::consts::PI).sqrt().max(1.0);
        let reach = 3.0 * radius + 2.0;
        let likeness = |k: usize, i: usize, j: usize| {
            let rgb = self.rgb(k, i, j);
            if (rgb[0] + rgb[1] + rgb[2]) / 3.0 < DARK {
                return 0.0;
            }
            (1.0 - distance(chroma(rgb), colour) / (0.5 * separation)).max(0.0)
        };
        let mut out = Vec::new();
        for k in held {
            // The grey position of the nearest frame the guide has.
            let &(_, g) = guide.iter().min_by_key(|g| g.0.abs_diff(k))?;
            let mut c = self.to_colour(g);
            let mut spread = 0.0;
            let mut found = true;
            for _ in 0..4 {
                let (mut m, mut sx, mut sy, mut sxx) = (0.0, 0.0, 0.0, 0.0);
                for (i, j) in self.around(c, reach) {
                    let v = likeness(k, i, j);
                    let (x, y) = (i as f64, j as f64);
                    m += v;
                    sx += v * x;
                    sy += v * y;
                    sxx += v * (x * x + y * y);
                }
                if m < 0.25 * object.len() as f64 {
                    found = false;
                    break;
                }
                c = [sx / m, sy / m];
                spread = (sxx / m - c[0] * c[0] - c[1] * c[1]).max(0.0).sqrt();
            }
            if found {
                out.push((k, self.to_grey(c), spread / self.scale as f64));
            }
        }
        Some(out)
    }
}

/// The mean of chromaticities; `None` for none.
fn mean(cs: impl Iterator<Item = [f64; 3]>) -> Option<[f64; 3]> {
    let (n, sum) = cs.fold((0usize, [0.0; 3]), |(n, s), c| {
        (n + 1, [s[0] + c[0], s[1] + c[1], s[2] + c[2]])
    });
    (n > 0).then(|| sum.map(|v| v / n as f64))
}

/// A colour's chromaticity: its r, g, b as shares of their sum.
fn chroma(rgb: [f32; 3]) -> [f64; 3] {
    let s = f64::from(rgb[0] + rgb[1] + rgb[2]) + 1e-3;
    rgb.map(|v| f64::from(v) / s)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames 10..30 of a 20×40 colour picture (grey 10×20 at scale 2): a grey wall, a red
    /// disc of radius 3 at row `ball(k)`, and a skin-coloured blob beside it on frames
    /// `hand`.
    fn scene(ball: impl Fn(usize) -> f64, hand: std::ops::Range<usize>) -> Vec<f32> {
        let (w, h) = (20, 40);
        let mut out = Vec::new();
        for k in 10..30 {
            let mut f = vec![0.5f32; 3 * w * h];
            for j in 0..h {
                for i in 0..w {
                    let (x, y) = (i as f64 - 9.5, j as f64 - ball(k));
                    let mut rgb = [0.5, 0.5, 0.5];
                    if hand.contains(&k) && (x - 4.5).powi(2) + (y - 1.0).powi(2) < 10.0 {
                        rgb = [0.85, 0.65, 0.55];
                    }
                    if x * x + y * y < 9.0 {
                        rgb = [0.8, 0.15, 0.15];
                    }
                    for c in 0..3 {
                        f[c * w * h + j * w + i] = rgb[c];
                    }
                }
            }
            out.extend(f);
        }
        out
    }

    /// `scene`'s frames as a grey 10×20 picture's at scale 2, from frame 10.
    fn on(frames: &[f32]) -> Hue<'_> {
        Hue {
            frames,
            first: 10,
            scale: 2,
            grey: (10, 20),
        }
    }

    /// A colour row's grey position from the centre.
    fn grey_row(row: f64) -> f64 {
        (row + 0.5) / 2.0 - 10.0
    }

    #[test]
    fn the_object_is_followed_by_its_colour_past_a_hand_beside_it() {
        let ball = |k: usize| 5.0 + 0.08 * (k as f64 - 10.0).powi(2);
        let frames = scene(ball, 10..16);
        let hue = on(&frames);
        // The grey guide pulled 1.5 grey pixels towards the hand on the hand's frames.
        let guide: Vec<(usize, [f64; 2])> = (10..30)
            .map(|k| {
                let pull = if k < 16 { 1.5 } else { 0.0 };
                (k, [pull, grey_row(ball(k))])
            })
            .collect();
        let out = hue
            .follow(&guide, 26, 10)
            .expect("a red ball on a grey wall");
        assert_eq!(out.len(), 20);
        for &(k, p, spread) in &out {
            let truth = grey_row(ball(k));
            assert!(p[0].abs() < 0.05, "frame {k}: x {}", p[0]);
            assert!(
                (p[1] - truth).abs() < 0.1,
                "frame {k}: y {} against {truth}",
                p[1]
            );
            // The disc's own: √(3²/2) colour pixels, 1.06 grey pixels.
            assert!((spread - 1.06).abs() < 0.1, "frame {k}: spread {spread}");
        }
    }

    #[test]
    fn an_object_of_the_walls_chromaticity_is_not_followed() {
        let frames: Vec<f32> = scene(|k| 5.0 + k as f64, 0..0)
            .chunks(3 * 20 * 40)
            .flat_map(|f| {
                // The ball grey: its red, green and blue alike.
                let plane = 20 * 40;
                (0..3 * plane).map(move |a| {
                    let p = a % plane;
                    (f[p] + f[p + plane] + f[p + 2 * plane]) / 3.0
                })
            })
            .collect();
        let hue = on(&frames);
        let guide: Vec<(usize, [f64; 2])> = (10..30)
            .map(|k| (k, [0.0, grey_row(5.0 + k as f64)]))
            .collect();
        assert!(hue.follow(&guide, 25, 10).is_none());
    }
}
