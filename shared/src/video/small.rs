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

/// The most bytes the look's pass writes and keeps of a recording at [`TRACK_SIDE`]: a longer
/// one's look goes alone, and the track decodes it itself as before (5 minutes at 30 frames a
/// second of 320×180). Bounds memory and the temporary file only; no decision reads it.
pub(super) const KEPT_AT_MOST: usize = 512 << 20;

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

/// The kept frames of `path`, taken: handed back where `whole` (the whole recording is asked
/// for) at this `size`, else let go (the track asked for a part, `--start` or `--end`: they
/// will not be asked for); none where another file's are kept, or the file changed since.
fn kept(path: &Path, size: (usize, usize), whole: bool) -> Option<SmallFrames> {
    let key = FileKey::of(path)?;
    taken(
        &mut KEPT.lock().unwrap_or_else(|e| e.into_inner()),
        &key,
        size,
        whole,
    )
}

/// [`kept`] from `slot`, for the file `key`.
fn taken(
    slot: &mut Option<(FileKey, SmallFrames)>,
    key: &FileKey,
    size: (usize, usize),
    whole: bool,
) -> Option<SmallFrames> {
    match slot.as_ref() {
        Some((k, _)) if k == key => slot
            .take()
            .map(|(_, f)| f)
            .filter(|f| whole && f.size == size),
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
    if side == TRACK_SIDE && picture == Picture::Grey {
        let whole = start.is_none() && end.is_none() && info.filter().is_none();
        if let Some(kept) = kept(input, (w, h), whole) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kept_frames_go_to_the_whole_asked_once_and_are_let_go_for_a_part() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.mp4"), dir.path().join("b.mp4"));
        std::fs::write(&a, b"a").unwrap();
        std::fs::write(&b, b"bb").unwrap();
        let (ka, kb) = (FileKey::of(&a).unwrap(), FileKey::of(&b).unwrap());
        let frames = || SmallFrames {
            pixels: vec![7; 2 * 4 * 3],
            size: (4, 3),
        };
        // The whole, at its size: handed back, once.
        let mut slot = Some((ka.clone(), frames()));
        assert!(
            taken(&mut slot, &kb, (4, 3), true).is_none(),
            "another file's"
        );
        assert_eq!(
            taken(&mut slot, &ka, (4, 3), true).map(|f| f.len()),
            Some(2)
        );
        assert!(slot.is_none() && taken(&mut slot, &ka, (4, 3), true).is_none());
        // A part of it, or another size: not handed back, and not held any longer.
        for (size, whole) in [((4, 3), false), ((8, 6), true)] {
            let mut slot = Some((ka.clone(), frames()));
            assert!(taken(&mut slot, &ka, size, whole).is_none());
            assert!(slot.is_none());
        }
    }
}
