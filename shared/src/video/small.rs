//! A recording decoded whole at a small size (the long side at most a given number of pixels,
//! a byte a pixel: its grey, or its colour's distance from grey), held in memory: what the
//! survey and the object's track read.

use super::decoded::SmallFrames;
use super::tools::{raw_frames, read_full, tool, trimmed_input, EVERY_FRAME};
use super::{VideoError, VideoInfo};
use std::path::Path;
use std::process::Stdio;
use std::sync::OnceLock;

/// The long side (pixels) at which the object's track reads a recording whole. The look at a
/// recording's fields (`fields::find`) decodes it at this size in the same pass, for the track
/// (one decode of a 1080p spring fewer: 0.6 s of its 6).
pub const TRACK_SIDE: usize = 320;

/// The long side of the survey's frames (`survey`).
pub const SURVEY_SIDE: usize = 160;

/// `input` (trimmed to `start`..`end` seconds) decoded to grey with its long side at most
/// `side` pixels (never enlarged), interlaced fields split as the probe found them. The whole
/// of a progressive recording at [`TRACK_SIDE`] or [`SURVEY_SIDE`] is the one its fields' look
/// decoded, where that was this process's last (and is not served twice: the track, or the
/// survey, holds it).
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
    if picture == Picture::Grey {
        let whole = start.is_none() && end.is_none() && info.filter().is_none();
        let kept = match side {
            TRACK_SIDE => super::kept::whole(input, (w, h), whole),
            SURVEY_SIDE => super::kept::surveyed(input, (w, h), whole),
            _ => None,
        };
        if let Some(kept) = kept {
            return Ok(kept);
        }
    }
    let n = w * h;
    if picture == Picture::Chroma && side == TRACK_SIDE {
        let whole = start.is_none() && end.is_none() && info.filter().is_none();
        if let Some(planes) = super::kept::colour(input, (w, h), whole) {
            let mut pixels = Vec::with_capacity(planes.len() / 3);
            planes
                .chunks_exact(3 * n)
                .for_each(|f| chroma(f, n, &mut pixels));
            return Ok(SmallFrames {
                pixels,
                size: (w, h),
            });
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
    let (format, planes) = match picture {
        Picture::Grey => ("gray", 1),
        Picture::Chroma => ("yuv444p", 3),
    };
    let (mut child, mut stdout) = raw_frames(cmd, input, format, Stdio::null())?;
    let mut pixels = Vec::new();
    let mut buf = vec![0u8; n * planes];
    while read_full(&mut stdout, &mut buf).is_ok_and(|k| k == buf.len()) {
        match picture {
            Picture::Grey => pixels.extend_from_slice(&buf),
            Picture::Chroma => chroma(&buf, n, &mut pixels),
        }
    }
    let _ = child.wait();
    Ok(SmallFrames {
        pixels,
        size: (w, h),
    })
}

/// Each of the `n` pixels' chroma of a frame's YUV 4:4:4 `planes`, onto `out`: its colour's
/// distance from grey, √((U − 128)² + (V − 128)²) rounded, from a table of every (U, V).
pub(super) fn chroma(planes: &[u8], n: usize, out: &mut Vec<u8>) {
    static TABLE: OnceLock<Vec<u8>> = OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..1usize << 16)
            .map(|uv| {
                let u = (uv >> 8) as f64 - 128.0;
                let v = (uv & 0xff) as f64 - 128.0;
                u.hypot(v).round().min(255.0) as u8
            })
            .collect()
    });
    let (u, v) = (&planes[n..2 * n], &planes[2 * n..3 * n]);
    out.extend(
        u.iter()
            .zip(v)
            .map(|(&u, &v)| table[(usize::from(u) << 8) | usize::from(v)]),
    );
}
