//! Regions of the survey's motion maps (`survey`): a light blur, the connected parts of what
//! moves, and their bounding boxes in map pixels.

/// A bounding box in map pixels, inclusive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bounds {
    pub x0: usize,
    pub y0: usize,
    pub x1: usize,
    pub y1: usize,
}

impl Bounds {
    /// The box of the pixels of a `w`-wide map where `inside` holds, if any.
    pub fn of(w: usize, n: usize, inside: impl Fn(usize) -> bool) -> Option<Bounds> {
        let mut b: Option<Bounds> = None;
        for i in (0..n).filter(|&i| inside(i)) {
            let (x, y) = (i % w, i / w);
            b = Some(match b {
                None => Bounds {
                    x0: x,
                    y0: y,
                    x1: x,
                    y1: y,
                },
                Some(b) => b.union(Bounds {
                    x0: x,
                    y0: y,
                    x1: x,
                    y1: y,
                }),
            });
        }
        b
    }

    pub fn union(self, o: Bounds) -> Bounds {
        Bounds {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }

    /// Widened by a fifth of its size (at least two pixels) each side, within a `w`×`h` map.
    pub fn with_margin(self, w: usize, h: usize) -> Bounds {
        let (mx, my) = (
            ((self.x1 - self.x0 + 1) / 5).max(2),
            ((self.y1 - self.y0 + 1) / 5).max(2),
        );
        Bounds {
            x0: self.x0.saturating_sub(mx),
            y0: self.y0.saturating_sub(my),
            x1: (self.x1 + mx).min(w - 1),
            y1: (self.y1 + my).min(h - 1),
        }
    }

    /// Its share of a `w`×`h` map.
    pub fn share(self, w: usize, h: usize) -> f64 {
        ((self.x1 - self.x0 + 1) * (self.y1 - self.y0 + 1)) as f64 / (w * h) as f64
    }
}

/// A 3×3 box blur, twice (spreads a thin moving edge over its neighbours).
pub fn blur(map: &[f32], w: usize, h: usize) -> Vec<f32> {
    let once = |m: &[f32]| -> Vec<f32> {
        (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as isize, (i / w) as isize);
                let (mut s, mut n) = (0.0, 0.0);
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let (a, b) = (x + dx, y + dy);
                        if a >= 0 && b >= 0 && (a as usize) < w && (b as usize) < h {
                            s += m[b as usize * w + a as usize];
                            n += 1.0;
                        }
                    }
                }
                s / n
            })
            .collect()
    };
    once(&once(map))
}

/// Labels of the 8-connected components of `on` (None where off) and their count.
pub fn components(on: &[bool], w: usize, h: usize) -> (Vec<Option<usize>>, usize) {
    let mut labels = vec![None; w * h];
    let mut count = 0;
    for start in 0..w * h {
        if !on[start] || labels[start].is_some() {
            continue;
        }
        let mut stack = vec![start];
        labels[start] = Some(count);
        while let Some(i) = stack.pop() {
            let (x, y) = ((i % w) as isize, (i / w) as isize);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (a, b) = (x + dx, y + dy);
                    if a < 0 || b < 0 || a as usize >= w || b as usize >= h {
                        continue;
                    }
                    let j = b as usize * w + a as usize;
                    if on[j] && labels[j].is_none() {
                        labels[j] = Some(count);
                        stack.push(j);
                    }
                }
            }
        }
        count += 1;
    }
    (labels, count)
}
