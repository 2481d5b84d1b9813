//! A picture and its halvings, each pixel the mean of four (the sizes `steady` seeks a
//! camera's shift at, from coarse to fine).

/// The sizes the shift is sought at, halving (a shake of eight pixels is two at the smallest),
/// and the smallest side a halving keeps.
const LEVELS: usize = 3;
const LEAST_SIDE: usize = 24;

/// A picture and its size.
pub(super) struct Level {
    pub pixels: Vec<u8>,
    pub size: (usize, usize),
}

impl Level {
    /// The picture at half the size, each pixel the mean of four.
    fn halved(&self) -> Level {
        let (w, h) = self.size;
        let (hw, hh) = (w / 2, h / 2);
        let at = |x: usize, y: usize| u16::from(self.pixels[y * w + x]);
        let pixels = (0..hh)
            .flat_map(|y| (0..hw).map(move |x| (x, y)))
            .map(|(x, y)| {
                let sum = at(2 * x, 2 * y)
                    + at(2 * x + 1, 2 * y)
                    + at(2 * x, 2 * y + 1)
                    + at(2 * x + 1, 2 * y + 1);
                ((sum + 2) / 4) as u8
            })
            .collect();
        Level {
            pixels,
            size: (hw, hh),
        }
    }

    /// This picture and its halvings while the smaller side keeps [`LEAST_SIDE`] pixels, at
    /// most [`LEVELS`] in all, the full size first.
    pub fn pyramid(pixels: &[u8], size: (usize, usize)) -> Vec<Level> {
        let mut levels = vec![Level {
            pixels: pixels.to_vec(),
            size,
        }];
        while levels.len() < LEVELS {
            let last = levels.last().expect("one level");
            if last.size.0.min(last.size.1) / 2 < LEAST_SIDE {
                break;
            }
            let half = last.halved();
            levels.push(half);
        }
        levels
    }
}
