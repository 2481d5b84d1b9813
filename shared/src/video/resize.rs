//! `FrameResizer`: crop a grey frame and area-average it down to the encoder's size, values in
//! [0, 1]; the same code for videos and image folders.

use super::Crop;

/// Area-average resampling weights: for each of `n_out` output cells over `n_in` inputs, the
/// (input index, weight) pairs, weights summing to 1.
fn area_weights(n_in: usize, n_out: usize) -> Vec<Vec<(usize, f32)>> {
    let scale = n_in as f64 / n_out as f64;
    (0..n_out)
        .map(|o| {
            let (a, b) = (o as f64 * scale, (o + 1) as f64 * scale);
            let mut w = Vec::new();
            let mut i = a.floor() as usize;
            while (i as f64) < b && i < n_in {
                let cover = (b.min(i as f64 + 1.0) - a.max(i as f64)).max(0.0);
                if cover > 0.0 {
                    w.push((i, (cover / scale) as f32));
                }
                i += 1;
            }
            w
        })
        .collect()
}

/// Crops a grey frame (`width` wide, bytes) and area-resizes it to `size`, values in [0, 1].
pub struct FrameResizer {
    crop: Crop,
    width: usize,
    cols: Vec<Vec<(usize, f32)>>,
    rows: Vec<Vec<(usize, f32)>>,
    row_buf: Vec<f32>,
}

impl FrameResizer {
    pub fn new(width: usize, crop: Crop, size: (usize, usize)) -> FrameResizer {
        FrameResizer {
            crop,
            width,
            cols: area_weights(crop.w, size.0),
            rows: area_weights(crop.h, size.1),
            row_buf: vec![0.0; crop.h * size.0],
        }
    }

    pub fn resize(&mut self, grey: &[u8]) -> Vec<f32> {
        let (cw, ch, ow) = (self.crop.w, self.crop.h, self.cols.len());
        for y in 0..ch {
            let row = &grey[(self.crop.y + y) * self.width + self.crop.x..][..cw];
            for (o, ws) in self.cols.iter().enumerate() {
                self.row_buf[y * ow + o] = ws.iter().map(|&(i, w)| row[i] as f32 * w).sum();
            }
        }
        let mut out = vec![0.0f32; self.rows.len() * ow];
        for (oy, ws) in self.rows.iter().enumerate() {
            for &(iy, w) in ws {
                for ox in 0..ow {
                    out[oy * ow + ox] += self.row_buf[iy * ow + ox] * w;
                }
            }
        }
        out.iter_mut()
            .for_each(|v| *v = (*v / 255.0).clamp(0.0, 1.0));
        out
    }
}

/// Moves `frame` (`size` = (width, height), one channel) by (dx, dy) pixels: its point p put at
/// p + (dx, dy), bilinearly, the edges repeated.
pub fn shifted(frame: &[f32], (w, h): (usize, usize), dx: f32, dy: f32) -> Vec<f32> {
    let at = |x: isize, y: isize| {
        let x = x.clamp(0, w as isize - 1) as usize;
        let y = y.clamp(0, h as isize - 1) as usize;
        frame[y * w + x]
    };
    let mut out = vec![0.0; w * h];
    for y in 0..h {
        for x in 0..w {
            let (sx, sy) = (x as f32 - dx, y as f32 - dy);
            let (x0, y0) = (sx.floor(), sy.floor());
            let (fx, fy) = (sx - x0, sy - y0);
            let (x0, y0) = (x0 as isize, y0 as isize);
            out[y * w + x] = (1.0 - fy) * ((1.0 - fx) * at(x0, y0) + fx * at(x0 + 1, y0))
                + fy * ((1.0 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_resize_averages_and_keeps_a_constant_image_constant() {
        let grey = vec![200u8; 7 * 5];
        let mut r = FrameResizer::new(
            7,
            Crop {
                x: 0,
                y: 0,
                w: 7,
                h: 5,
            },
            (3, 2),
        );
        let out = r.resize(&grey);
        assert!(
            out.iter().all(|v| (v - 200.0 / 255.0).abs() < 1e-5),
            "{out:?}"
        );
        // A 4×2 crop of a ramp halved in width: each output is the mean of two inputs.
        let ramp: Vec<u8> = (0..4 * 2).map(|i| (i * 10) as u8).collect();
        let mut r = FrameResizer::new(
            4,
            Crop {
                x: 0,
                y: 0,
                w: 4,
                h: 2,
            },
            (2, 1),
        );
        let out = r.resize(&ramp);
        let expect = [
            (0.0 + 10.0 + 40.0 + 50.0) / 4.0,
            (20.0 + 30.0 + 60.0 + 70.0) / 4.0,
        ];
        for (o, e) in out.iter().zip(expect) {
            assert!((o - e / 255.0).abs() < 1e-5, "{out:?}");
        }
    }

    #[test]
    fn a_whole_pixel_shift_moves_the_picture() {
        let (w, h) = (7, 5);
        let mut f = vec![0.0f32; w * h];
        f[2 * w + 2] = 1.0;
        let g = shifted(&f, (w, h), 1.0, 2.0);
        assert!((g[4 * w + 3] - 1.0).abs() < 1e-6);
        assert!((g.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        // Half a pixel: shared between two, the edge repeated where the picture leaves.
        let g = shifted(&f, (w, h), -0.5, 0.0);
        assert!((g[2 * w + 1] - 0.5).abs() < 1e-6 && (g[2 * w + 2] - 0.5).abs() < 1e-6);
    }
}
