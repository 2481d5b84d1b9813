//! A recording decoded whole at a small size (the long side at most a given number of pixels,
//! a byte a pixel: its grey, or its colour's distance from grey), held in memory: what the
//! survey and the object's track read.

use super::tools::{raw_frames, read_full, tool, trimmed_input, EVERY_FRAME};
use super::{FileKey, VideoError, VideoInfo};
use std::path::Path;
use std::sync::Mutex;

/// The long side (pixels) at which the object's track reads a recording whole. The look at a
/// recording's fields (`fields::find`) decodes it at this size in the same pass, for the track
/// (one decode of a 1080p spring fewer: 0.6 s of its 6).
pub const TRACK_SIDE: usize = 320;

/// Frames of one size (grey, or chroma: `small_chroma`), row-major, one after another.
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
/// `side` pixels (never enlarged), interlaced fields split as the probe found them. The whole
/// of a progressive recording at [`TRACK_SIDE`] is the one its fields' look decoded, where
/// that was this process's last (and is not served twice: the track holds it).
pub fn small_frames(
    input: &Path,
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    side: usize,
) -> Result<SmallFrames, VideoError> {
    decode_small(input, info, span, side, Picture::Grey)
}

/// `input` decoded as [`small_frames`] decodes it, each pixel its colour's distance from grey
/// instead of its brightness (the chroma: √((U − 128)² + (V − 128)²) of its YUV, 0 for every
/// grey): a coloured object before a wall as bright as it stands out here and not in the grey.
pub fn small_chroma(
    input: &Path,
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    side: usize,
) -> Result<SmallFrames, VideoError> {
    decode_small(input, info, span, side, Picture::Chroma)
}

/// The size of a `width`×`height` picture with its long side at most `side` (never enlarged).
pub(super) fn small_size((width, height): (usize, usize), side: usize) -> (usize, usize) {
    let scale = (side as f64 / width.max(height) as f64).min(1.0);
    let w = ((width as f64 * scale).round() as usize).max(2);
    let h = ((height as f64 * scale).round() as usize).max(2);
    (w, h)
}

/// ffmpeg's filter that makes a frame `size` (w, h), its pixels area-averaged.
pub(super) fn small_filter((w, h): (usize, usize)) -> String {
    format!("scale={w}:{h}:flags=area")
}

/// The whole of the last recording whose fields were looked at, progressive, at
/// [`TRACK_SIDE`], decoded in the look's pass; and the file it is of.
static KEPT: Mutex<Option<(FileKey, SmallFrames)>> = Mutex::new(None);

/// Keeps `frames` (the whole of the progressive recording at `path` at [`TRACK_SIDE`]) for
/// [`small_frames`], in place of any other file's.
pub(super) fn keep(path: &Path, frames: SmallFrames) {
    let Some(key) = FileKey::of(path) else {
        return;
    };
    *KEPT.lock().unwrap_or_else(|e| e.into_inner()) = Some((key, frames));
}

/// The kept frames of `path` of this `size`, taken (none where another file's or another
/// size's are kept, or where the file changed since).
fn kept(path: &Path, size: (usize, usize)) -> Option<SmallFrames> {
    let key = FileKey::of(path)?;
    let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
    match kept.as_ref() {
        Some((k, f)) if *k == key && f.size == size => kept.take().map(|(_, f)| f),
        _ => None,
    }
}

/// What a small frame's byte holds.
#[derive(Clone, Copy, PartialEq)]
enum Picture {
    Grey,
    Chroma,
}

fn decode_small(
    input: &Path,
    info: &VideoInfo,
    (start, end): (Option<f64>, Option<f64>),
    side: usize,
    picture: Picture,
) -> Result<SmallFrames, VideoError> {
    let (w, h) = small_size((info.width, info.height), side);
    let whole = start.is_none() && end.is_none() && info.filter().is_none();
    if whole && side == TRACK_SIDE && picture == Picture::Grey {
        if let Some(kept) = kept(input, (w, h)) {
            return Ok(kept);
        }
    }
    let mut cmd = tool("ffmpeg");
    cmd.args(["-v", "error", "-nostdin"]);
    trimmed_input(&mut cmd, input, start, end);
    cmd.args(EVERY_FRAME).args([
        "-vf",
        &match info.filter() {
            Some(fields) => format!("{fields},{}", small_filter((w, h))),
            None => small_filter((w, h)),
        },
    ]);
    let n = w * h;
    let (format, planes) = match picture {
        Picture::Grey => ("gray", 1),
        Picture::Chroma => ("yuv444p", 3),
    };
    let (mut child, mut stdout) = raw_frames(cmd, input, format)?;
    let mut pixels = Vec::new();
    let mut buf = vec![0u8; n * planes];
    while read_full(&mut stdout, &mut buf).is_ok_and(|k| k == buf.len()) {
        match picture {
            Picture::Grey => pixels.extend_from_slice(&buf),
            Picture::Chroma => pixels.extend((0..n).map(|p| {
                let u = buf[n + p] as f64 - 128.0;
                let v = buf[2 * n + p] as f64 - 128.0;
                u.hypot(v).round().min(255.0) as u8
            })),
        }
    }
    let _ = child.wait();
    Ok(SmallFrames {
        pixels,
        size: (w, h),
    })
}
