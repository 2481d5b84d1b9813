//! Contact sheets: a grid of frames (rows = clips, columns = time) as a PNG, grey or colour.

use image::{DynamicImage, GrayImage, Luma, Rgb, RgbImage};

/// Lays out `rows` clips (indices into the N axis) × all T frames of a [N, T, C, H, W] array,
/// each frame magnified `scale` times, separated by 2-pixel grey gutters: in colour when C = 3,
/// otherwise the first channel in grey.
pub fn contact_sheet(data: &[f32], shape: [usize; 5], rows: &[usize], scale: u32) -> DynamicImage {
    let [_, t, c, h, w] = shape;
    let gutter = 2u32;
    let (fw, fh) = (w as u32 * scale, h as u32 * scale);
    let width = t as u32 * (fw + gutter) + gutter;
    let height = rows.len() as u32 * (fh + gutter) + gutter;
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let mut grey = GrayImage::from_pixel(width, height, Luma([96]));
    let mut colour = RgbImage::from_pixel(width, height, Rgb([96, 96, 96]));
    for (r, &n) in rows.iter().enumerate() {
        for k in 0..t {
            let base = ((n * t + k) * c) * h * w;
            let (x0, y0) = (
                gutter + k as u32 * (fw + gutter),
                gutter + r as u32 * (fh + gutter),
            );
            for y in 0..fh {
                for x in 0..fw {
                    let at = (y / scale) as usize * w + (x / scale) as usize;
                    if c == 3 {
                        let px = [0, 1, 2].map(|ch| byte(data[base + ch * h * w + at]));
                        colour.put_pixel(x0 + x, y0 + y, Rgb(px));
                    } else {
                        grey.put_pixel(x0 + x, y0 + y, Luma([byte(data[base + at])]));
                    }
                }
            }
        }
    }
    if c == 3 {
        DynamicImage::ImageRgb8(colour)
    } else {
        DynamicImage::ImageLuma8(grey)
    }
}

/// Encodes an image as PNG bytes.
pub fn encode_png(img: &DynamicImage) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .expect("PNG encoding into memory cannot fail");
    out.into_inner()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lays_out_frames_in_a_grid() {
        // 2 clips × 3 frames of 2×2; frame k of clip n has value (n*3+k)/10.
        let data: Vec<f32> = (0..6)
            .flat_map(|i| std::iter::repeat_n(i as f32 / 10.0, 4))
            .collect();
        let img = contact_sheet(&data, [2, 3, 1, 2, 2], &[1], 2);
        let grey = img.as_luma8().unwrap();
        assert_eq!(grey.dimensions(), (3 * 6 + 2, 6 + 2));
        // Clip 1, frame 2 → value 0.5 → 128.
        assert_eq!(grey.get_pixel(2 + 2 * 6, 2)[0], 128);
        assert_eq!(grey.get_pixel(0, 0)[0], 96);
        assert!(!encode_png(&img).is_empty());
    }
}
