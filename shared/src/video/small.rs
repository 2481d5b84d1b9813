//! A recording decoded whole to grey at a small size (the long side at most a given number of
//! pixels, a byte a pixel), held in memory: what the survey and the object's track read.

use super::tools::{gray_frames, read_full, tool, trimmed_input, EVERY_FRAME};
use super::{VideoError, VideoInfo};
use std::path::Path;

/// Grey frames of one size, row-major, one after another.
pub struct SmallFrames {
    pub pixels: Vec<u8>,
    pub size: (usize, usize),
}

impl SmallFrames {
    /// How many frames were decoded.
    pub fn len(&self) -> usize {
        self.pixels.len() / (self.size.0 * self.size.1).max(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Frame `i`.
    pub fn frame(&self, i: usize) -> &[u8] {
        let n = self.size.0 * self.size.1;
        &self.pixels[i * n..(i + 1) * n]
    }
}

/// `input` (trimmed to `start`..`end` seconds) decoded to grey with its long side at most
/// `side` pixels (never enlarged), interlaced fields split as the probe found them.
pub fn small_frames(
    input: &Path,
    info: &VideoInfo,
    (start, end): (Option<f64>, Option<f64>),
    side: usize,
) -> Result<SmallFrames, VideoError> {
    let scale = (side as f64 / info.width.max(info.height) as f64).min(1.0);
    let w = ((info.width as f64 * scale).round() as usize).max(2);
    let h = ((info.height as f64 * scale).round() as usize).max(2);
    let mut cmd = tool("ffmpeg")?;
    cmd.args(["-v", "error", "-nostdin"]);
    trimmed_input(&mut cmd, input, start, end);
    cmd.args(EVERY_FRAME).args([
        "-vf",
        &match info.filter() {
            Some(fields) => format!("{fields},scale={w}:{h}:flags=area"),
            None => format!("scale={w}:{h}:flags=area"),
        },
    ]);
    let (mut child, mut stdout) = gray_frames(cmd, input)?;
    let mut pixels = Vec::new();
    let mut buf = vec![0u8; w * h];
    while read_full(&mut stdout, &mut buf).is_ok_and(|n| n == buf.len()) {
        pixels.extend_from_slice(&buf);
    }
    let _ = child.wait();
    Ok(SmallFrames {
        pixels,
        size: (w, h),
    })
}
