//! Videos drawn pixel by pixel for the end-to-end tests: grey PNG frames, encoded losslessly.

use std::path::{Path, PathBuf};

/// `frames` grey frames of `size` (w, h), pixel (x, y) of frame k `pixel(k, x, y)`, written as
/// `dir/frames/frame1.png` … and encoded as the lossless grey video `dir/name` at `fps`.
pub fn gray_video(
    dir: &Path,
    name: &str,
    (frames, fps): (usize, u32),
    size: (u32, u32),
    pixel: impl Fn(usize, u32, u32) -> u8,
) -> PathBuf {
    let pngs = dir.join("frames");
    std::fs::create_dir_all(&pngs).unwrap();
    for k in 0..frames {
        let img = image::GrayImage::from_fn(size.0, size.1, |x, y| image::Luma([pixel(k, x, y)]));
        img.save(pngs.join(format!("frame{}.png", k + 1))).unwrap();
    }
    let video = dir.join(name);
    super::encode_lossless(&pngs, &video, fps);
    video
}
