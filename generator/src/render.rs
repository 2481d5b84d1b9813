//! `Canvas`: anti-aliased discs and polygons drawn with tiny-skia at 2× and box-filtered into
//! f32 frames in [0, 1].

use tiny_skia::{FillRule, Paint, PathBuilder, PixmapMut, Transform};

/// A disc to draw: centre, radius (pixels) and grey level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    pub cx: f32,
    pub cy: f32,
    pub radius: f32,
    pub grey: f32,
}

/// Each output pixel is the mean of SUPERSAMPLE² pixels of the tiny-skia canvas. tiny-skia's
/// 8-bit anti-aliasing alone leaves a size-dependent error in the drawn area (γ1 read from the
/// scale set came out 0.56 % high at 1×; 0.004 % at 2×).
const SUPERSAMPLE: usize = 2;

/// Vertices of the polygon that stands for a circle. tiny-skia's own `from_circle` flattens
/// its curves into a number of segments that jumps with the radius, which makes the drawn area
/// jump too; a fixed fine polygon keeps the area exactly proportional to r².
const CIRCLE_VERTICES: usize = 96;

/// A reusable tiny-skia canvas of `size`×`size` output pixels (one per worker thread). It keeps
/// the coverage of the last disc drawn, so a disc of unchanged geometry (the intensity scene)
/// is rasterised once and only re-scaled.
pub struct Canvas {
    /// RGBA8 scratch for tiny-skia, as large as the supersampled frame; each disc is drawn
    /// into a pixmap over its bounding box only.
    scratch: Vec<u8>,
    paint: Paint<'static>,
    size: usize,
    unit_circle: Vec<(f32, f32)>,
    /// Coverage in [0, 1] of the last geometry drawn, at output resolution.
    coverage: Vec<f32>,
    last_geometry: Option<(f32, f32, f32)>,
}

impl Canvas {
    pub fn new(size: usize) -> Canvas {
        let mut paint = Paint::default();
        paint.set_color_rgba8(255, 255, 255, 255);
        paint.anti_alias = true;
        let wide = size * SUPERSAMPLE;
        Canvas {
            scratch: vec![0; wide * wide * 4],
            paint,
            size,
            unit_circle: (0..CIRCLE_VERTICES)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / CIRCLE_VERTICES as f64;
                    (a.cos() as f32, a.sin() as f32)
                })
                .collect(),
            coverage: vec![0.0; size * size],
            last_geometry: None,
        }
    }

    /// Anti-aliased coverage of `disc` (0 outside, 1 inside) times its grey level, into `out`
    /// (row-major, size² values). The grey level is applied in f32 after rasterising the
    /// coverage, so brightness is exact rather than quantised to 1/255.
    pub fn render_frame(&mut self, disc: &Disc, out: &mut [f32]) {
        let geometry = (disc.cx, disc.cy, disc.radius);
        if self.last_geometry != Some(geometry) {
            self.rasterise_disc(disc);
            self.last_geometry = Some(geometry);
        }
        for (o, c) in out.iter_mut().zip(&self.coverage) {
            *o = c * disc.grey;
        }
    }

    /// Vertices of the regular `CIRCLE_VERTICES`-gon inscribed in a circle.
    pub fn circle_points(&self, cx: f32, cy: f32, r: f32) -> Vec<(f32, f32)> {
        self.unit_circle
            .iter()
            .map(|&(c, s)| (cx + r * c, cy + r * s))
            .collect()
    }

    /// Draws an opaque filled polygon (pixel coordinates) of grey level `grey` over `out`: a
    /// pixel covered by a fraction c becomes (1 − c)·below + c·grey ("over" compositing), so
    /// every pixel stays affine in the shape's grey level (an LED's brightness shows linearly).
    pub fn draw_polygon(&mut self, points: &[(f32, f32)], grey: f32, out: &mut [f32]) {
        self.rasterise(points);
        self.last_geometry = None;
        for (o, c) in out.iter_mut().zip(&self.coverage) {
            *o += c * (grey - *o);
        }
    }

    fn rasterise_disc(&mut self, disc: &Disc) {
        let pts = self.circle_points(disc.cx, disc.cy, disc.radius);
        self.rasterise(&pts);
    }

    /// Coverage of the polygon at output resolution into `self.coverage`: tiny-skia draws it at
    /// SUPERSAMPLE× over its bounding box only, then each output pixel averages its sub-pixels.
    fn rasterise(&mut self, points: &[(f32, f32)]) {
        self.coverage.fill(0.0);
        if points.len() < 3 {
            return;
        }
        let (mut xmin, mut xmax, mut ymin, mut ymax) = (f32::MAX, f32::MIN, f32::MAX, f32::MIN);
        for &(x, y) in points {
            (xmin, xmax, ymin, ymax) = (xmin.min(x), xmax.max(x), ymin.min(y), ymax.max(y));
        }
        let lo = |c: f32| ((c.floor().max(0.0)) as usize).min(self.size);
        let hi = |c: f32| ((c.ceil().max(0.0)) as usize + 1).min(self.size);
        let (x0, x1, y0, y1) = (lo(xmin), hi(xmax), lo(ymin), hi(ymax));
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let (bw, bh) = ((x1 - x0) * SUPERSAMPLE, (y1 - y0) * SUPERSAMPLE);
        let ss = SUPERSAMPLE as f32;
        let mut pb = PathBuilder::new();
        for (k, &(x, y)) in points.iter().enumerate() {
            let (px, py) = ((x - x0 as f32) * ss, (y - y0 as f32) * ss);
            if k == 0 {
                pb.move_to(px, py);
            } else {
                pb.line_to(px, py);
            }
        }
        pb.close();
        let bytes = &mut self.scratch[..bw * bh * 4];
        bytes.fill(0);
        let mut pixmap =
            PixmapMut::from_bytes(bytes, bw as u32, bh as u32).expect("non-empty bounding box");
        if let Some(path) = pb.finish() {
            pixmap.fill_path(
                &path,
                &self.paint,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
        let norm = 1.0 / (255.0 * (SUPERSAMPLE * SUPERSAMPLE) as f32);
        let data = &self.scratch[..bw * bh * 4];
        for y in 0..y1 - y0 {
            let out_row = &mut self.coverage[(y0 + y) * self.size + x0..(y0 + y) * self.size + x1];
            for (x, o) in out_row.iter_mut().enumerate() {
                let mut acc = 0u32;
                for dy in 0..SUPERSAMPLE {
                    let base = ((y * SUPERSAMPLE + dy) * bw + x * SUPERSAMPLE) * 4 + 3;
                    for dx in 0..SUPERSAMPLE {
                        acc += data[base + dx * 4] as u32;
                    }
                }
                *o = acc as f32 * norm;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moments(out: &[f32], size: usize) -> (f32, f32) {
        let mass: f32 = out.iter().sum();
        let cx = out
            .iter()
            .enumerate()
            .map(|(i, v)| (i % size) as f32 * v)
            .sum::<f32>()
            / mass;
        (mass, cx)
    }

    #[test]
    fn coverage_matches_the_disc_area_and_centre() {
        let size = 50;
        let mut c = Canvas::new(size);
        let mut out = vec![0.0; size * size];
        for r in [4.0f32, 9.0, 11.3, 17.0] {
            let d = Disc {
                cx: 23.3,
                cy: 25.0,
                radius: r,
                grey: 0.5,
            };
            c.render_frame(&d, &mut out);
            let (mass, cx) = moments(&out, size);
            let area = std::f32::consts::PI * r * r * 0.5;
            assert!((mass / area - 1.0).abs() < 0.005, "r {r}: {mass} vs {area}");
            // Pixel i covers [i, i+1), so its centre is i + 0.5.
            assert!((cx + 0.5 - 23.3).abs() < 0.01, "{cx}");
            assert!(out.iter().all(|v| (0.0..=0.5).contains(v)));
        }
    }

    #[test]
    fn cached_geometry_only_rescales() {
        let size = 20;
        let mut c = Canvas::new(size);
        let (mut a, mut b) = (vec![0.0; size * size], vec![0.0; size * size]);
        let d = Disc {
            cx: 10.0,
            cy: 10.0,
            radius: 6.0,
            grey: 1.0,
        };
        c.render_frame(&d, &mut a);
        c.render_frame(&Disc { grey: 0.25, ..d }, &mut b);
        assert!(a.iter().zip(&b).all(|(x, y)| (x * 0.25 - y).abs() < 1e-7));
    }
}
