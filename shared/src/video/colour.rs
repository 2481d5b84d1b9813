//! `colour_frames`: a span of a video's frames in colour (ffmpeg → planar RGB through a pipe),
//! each plane cropped and area-resized as the grey decode does, for what colour alone tells
//! apart (a red ball from the skin of the hand that lets it go: `estimate`'s descent).

use super::tools::{raw_frames, read_full, tool, trimmed_input, EVERY_FRAME};
use super::{bad, Crop, FrameResizer, VideoError, VideoInfo, VideoOptions};
use std::ops::Range;
use std::path::Path;
use std::process::Stdio;

/// Frames `frames` (indices of the grey decode of `input` with `opts`: the same trim and
/// fields, every frame as it is) in colour, [F, 3, H, W] (red, green, blue) in [0, 1], each
/// plane cropped to `opts.crop` and resized to `size`. Only for a video whose decoded frames
/// are its own (not resampled onto an even clock: the indices would not match).
pub fn colour_frames(
    input: &Path,
    info: &VideoInfo,
    opts: &VideoOptions,
    frames: Range<usize>,
    size: (usize, usize),
) -> Result<Vec<f32>, VideoError> {
    let mut cmd = tool("ffmpeg");
    cmd.args(["-v", "error", "-nostdin"]);
    trimmed_input(&mut cmd, input, opts.start, opts.end);
    if let Some(filter) = info.filter() {
        cmd.args(["-vf", &filter]);
    }
    cmd.args(EVERY_FRAME)
        .args(["-frames:v", &frames.end.to_string()]);
    let (mut child, mut stdout) = raw_frames(cmd, input, "gbrp", Stdio::null())?;
    let plane = info.width * info.height;
    let mut buf = vec![0u8; 3 * plane];
    let crop = Crop::of(opts, info);
    let mut resizer = FrameResizer::new(info.width, crop, size);
    let mut out = Vec::with_capacity(frames.len() * 3 * size.0 * size.1);
    let mut k = 0;
    while k < frames.end {
        match read_full(&mut stdout, &mut buf) {
            Ok(n) if n == buf.len() => {}
            Ok(_) => break,
            Err(e) => return Err(bad(input, format!("reading ffmpeg's output: {e}"))),
        }
        if k >= frames.start {
            // gbrp: the green plane, the blue, the red.
            for p in [2, 0, 1] {
                out.extend(resizer.resize(&buf[p * plane..(p + 1) * plane]));
            }
        }
        k += 1;
    }
    drop(stdout);
    let _ = child.wait();
    if k < frames.end {
        return Err(bad(
            input,
            format!(
                "its colour frames ended after {k}, before frame {}",
                frames.end
            ),
        ));
    }
    Ok(out)
}
