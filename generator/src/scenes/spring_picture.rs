//! The spring scene's picture: DejaVu Sans Bold digits drawn anti-aliased at sub-pixel
//! positions, and the fixed cluttered backdrop they move over.

use crate::sampling::sample_rng;
use ab_glyph::{point, Font, FontRef, Glyph, PxScale, ScaleFont};
use rand::Rng;
use std::f64::consts::TAU;
use std::sync::OnceLock;

/// Height of a drawn digit (px).
const DIGIT_HEIGHT: f32 = 20.0;
/// The digits of body one and body two.
const DIGITS: [char; 2] = ['5', '0'];
/// The font, the scale that makes the digits [`DIGIT_HEIGHT`] high, and each digit's offset from
/// its origin to the centre of its ink.
struct Digits {
    font: FontRef<'static>,
    scale: PxScale,
    centres: [(f32, f32); 2],
}

fn digits() -> &'static Digits {
    static DIGITS_CELL: OnceLock<Digits> = OnceLock::new();
    DIGITS_CELL.get_or_init(|| {
        let font = FontRef::try_from_slice(dejavu::sans::bold()).expect("DejaVu Sans Bold parses");
        // Exact ink bounds in font units (y up).
        let ink = DIGITS.map(|c| {
            font.outline(font.glyph_id(c))
                .expect("a digit has an outline")
                .bounds
        });
        // ab_glyph gives these bounds with min.y at the top, so heights come out negative.
        let tallest = ink.iter().map(|b| b.height().abs()).fold(0.0f32, f32::max);
        let units_per_px = tallest / DIGIT_HEIGHT;
        let scale = PxScale::from(font.height_unscaled() / units_per_px);
        let factor = font.as_scaled(scale).h_scale_factor();
        // From the glyph's origin (on the baseline, y down) to the centre of its ink.
        let centres = ink.map(|b| {
            (
                (b.min.x + b.max.x) / 2.0 * factor,
                -(b.min.y + b.max.y) / 2.0 * factor,
            )
        });
        Digits {
            font,
            scale,
            centres,
        }
    })
}

/// Adds digit `which` centred at (x, y) to `coverage` (size² values, clamped to 1).
pub(super) fn draw_digit(which: usize, x: f64, y: f64, size: usize, coverage: &mut [f32]) {
    let d = digits();
    let (cx, cy) = d.centres[which];
    let glyph: Glyph = d
        .font
        .glyph_id(DIGITS[which])
        .with_scale_and_position(d.scale, point(x as f32 - cx, y as f32 - cy));
    if let Some(outline) = d.font.outline_glyph(glyph) {
        let b = outline.px_bounds();
        outline.draw(|gx, gy, c| {
            let (px, py) = (b.min.x as i64 + gx as i64, b.min.y as i64 + gy as i64);
            if (0..size as i64).contains(&px) && (0..size as i64).contains(&py) {
                let v = &mut coverage[py as usize * size + px as usize];
                *v = (*v + c).min(1.0);
            }
        });
    }
}

/// The fixed cluttered backdrop at (x, y) ∈ [0, 1]² for colour channel `ch` (all equal in grey):
/// broad waves and a dozen hard-edged patches and bars drawn once from a fixed seed, darkened
/// to at most 0.2 as PAIG darkens its CIFAR image.
pub(super) fn backdrop(x: f64, y: f64, ch: usize) -> f64 {
    static PATCHES: OnceLock<Vec<[f64; 8]>> = OnceLock::new();
    let patches = PATCHES.get_or_init(|| {
        let mut rng = sample_rng(0x5eed_5b71, 0);
        (0..12)
            .map(|_| {
                let mut p = [0.0; 8];
                for v in &mut p {
                    *v = rng.random_range(0.0..1.0);
                }
                p
            })
            .collect()
    });
    let phase = ch as f64 * 1.3;
    let mut v = 0.45
        + 0.2 * (TAU * (1.7 * x + 0.6 * y) + phase).sin()
        + 0.15 * (TAU * (0.4 * x - 2.3 * y) + 2.0 * phase).sin();
    for p in patches {
        // Patch: centre (p0, p1), half-size (0.04 + 0.12·p2, 0.04 + 0.12·p3), a bar if p4 > 0.7.
        let (hx, hy) = if p[4] > 0.7 {
            (0.3, 0.015)
        } else {
            (0.04 + 0.12 * p[2], 0.04 + 0.12 * p[3])
        };
        if (x - p[0]).abs() < hx && (y - p[1]).abs() < hy {
            v = p[5 + ch % 3];
        }
    }
    0.2 * v.clamp(0.0, 1.0)
}
