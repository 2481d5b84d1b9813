//! One decode for every candidate of a model choice: the frames of the last recording decoded
//! by a candidate are kept, and a later candidate asking for the same frames (file, frame
//! rate, crop, trim and size: its clips may be cut otherwise) gets a copy, its clips cut again.
//! Measured on the shared pendulum recording: 1.9 s of decoding per candidate.

use physvid_shared::video::{self, Crop, DecodedVideo, VideoError, VideoInfo, VideoOptions};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What the decoded frames depend on.
#[derive(Debug, Clone, PartialEq)]
struct Key {
    input: PathBuf,
    /// The file's (or folder's) length and modification time: a file rewritten in place is
    /// decoded again.
    stamp: Option<(u64, std::time::SystemTime)>,
    fps: Option<u64>,
    crop: Option<Crop>,
    start: Option<u64>,
    end: Option<u64>,
    size: (usize, usize),
}

impl Key {
    fn of(input: &Path, opts: &VideoOptions) -> Key {
        Key {
            input: input.to_path_buf(),
            stamp: std::fs::metadata(input)
                .ok()
                .and_then(|m| Some((m.len(), m.modified().ok()?))),
            fps: opts.fps.map(f64::to_bits),
            crop: opts.crop,
            start: opts.start.map(f64::to_bits),
            end: opts.end.map(f64::to_bits),
            size: opts.size,
        }
    }
}

/// The last decode kept by [`decode`].
static LAST: Mutex<Option<(Key, DecodedVideo)>> = Mutex::new(None);

/// `video::decode`, kept for (and served from) the next call with the same frames when `keep`
/// (a candidate of a model choice); without it nothing is kept.
pub fn decode(
    input: &Path,
    opts: &VideoOptions,
    info: Option<VideoInfo>,
    keep: bool,
) -> Result<DecodedVideo, VideoError> {
    if !keep {
        return video::decode(input, opts, info);
    }
    let key = Key::of(input, opts);
    let mut last = LAST.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((k, d)) = last.as_ref() {
        let count = d.frame_count();
        // Too few frames for this candidate's clip: decoded again, for decode's own error.
        if *k == key && count > (opts.frames_per_clip - 1).saturating_mul(opts.stride) {
            let mut d = d.clone();
            d.keep(0, count - 1, opts);
            return Ok(d);
        }
    }
    let d = video::decode(input, opts, info)?;
    *last = Some((key, d.clone()));
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_tells_apart_what_changes_the_frames_and_not_the_cut() {
        let opts = VideoOptions {
            fps: Some(30.0),
            crop: None,
            start: None,
            end: Some(4.0),
            size: (32, 24),
            frames_per_clip: 20,
            stride: 3,
            hop: None,
            max_clips: 500,
        };
        let p = Path::new("a.mp4");
        let recut = VideoOptions {
            frames_per_clip: 12,
            stride: 7,
            hop: Some(2),
            ..opts.clone()
        };
        assert_eq!(Key::of(p, &opts), Key::of(p, &recut));
        let moved = VideoOptions {
            end: Some(4.5),
            ..opts.clone()
        };
        assert_ne!(Key::of(p, &opts), Key::of(p, &moved));
        assert_ne!(Key::of(p, &opts), Key::of(Path::new("b.mp4"), &opts));
        let cropped = VideoOptions {
            crop: Some(Crop {
                x: 0,
                y: 0,
                w: 10,
                h: 10,
            }),
            ..opts.clone()
        };
        assert_ne!(Key::of(p, &opts), Key::of(p, &cropped));
    }
}
