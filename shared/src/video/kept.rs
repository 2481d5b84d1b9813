//! What the look at a recording's fields (`fields::picture::look`) decoded beside it, kept for
//! the later reads of the same file, so that a run decodes a short recording once: the whole at
//! the track's size for the object's track (`small_frames`), at the survey's for the survey,
//! and the whole at its own size for the latent's frames (`decode`, served by [`served`]: the very bytes ffmpeg gives). Each
//! is handed out once and then let go.
//!
//! Measured on the shared recordings: each start of ffmpeg costs 0.05 s (its libraries'
//! linking), the whole of a 0.07-s decode of a roll; writing a long recording's frames at their
//! own size to the temporary file costs more than decoding them again ([`LARGE_AT_MOST`]), and
//! frames kept smaller (640 or 960 pixels wide) moved the latent's answers by up to 3 % (the
//! jar's k from −0.9 % to +2.2 %, the fast spring's grade to doubtful): only a short
//! recording's frames are kept, and at their own size.

use super::decoded::SmallFrames;
use super::{Crop, FileKey, FrameResizer, VideoInfo, VideoOptions};
use std::path::Path;
use std::sync::Mutex;

/// The most bytes the look's pass writes and keeps of a recording at its own size: a longer one's
/// latent decodes it itself. Measured (three runs each): the tree's 76 MB kept, its run 0.17 s
/// faster (3.30 against 3.47 s); the pendulum's 300 MB (22 s at 640×360) and the fast 1080p
/// spring's 300 MB, 0.1–0.8 s and 0.3 s slower and 100–200 MB more memory (writing and reading
/// back the frames costs more than decoding them again). No decision reads it.
pub(super) const LARGE_AT_MOST: usize = 96 << 20;

/// The whole of a recording decoded in the look's pass: at the track's size (`TRACK_SIDE`),
/// at the survey's (`SURVEY_SIDE`) and at its own.
#[derive(Default)]
pub(crate) struct Wholes {
    pub whole: Option<SmallFrames>,
    pub survey: Option<SmallFrames>,
    pub large: Option<SmallFrames>,
    /// The whole at the track's size in colour: each frame's YUV 4:4:4 planes in turn.
    pub colour: Option<Vec<u8>>,
}

/// One kept recording: the file it is of, and its frames.
type Slot = Mutex<Option<(FileKey, SmallFrames)>>;

/// The whole at the track's size of the last progressive recording looked at.
static WHOLE: Slot = Mutex::new(None);
/// The whole at the survey's size of the last progressive recording looked at.
static SURVEY: Slot = Mutex::new(None);
/// The whole at the track's size in colour (its YUV planes, three bytes a pixel) of the last
/// progressive recording looked at.
static COLOUR: Slot = Mutex::new(None);
/// The whole at its own size of the last progressive recording looked at, where its look's
/// pass reported no error (a damaged file is decoded again, and its damage reported).
static LARGE: Slot = Mutex::new(None);

/// Keeps the `wholes` (at the track's size, the survey's and its own) of the progressive
/// recording at `path`, in place of any other file's.
pub(super) fn keep(path: &Path, wholes: Wholes) {
    let key = FileKey::of(path);
    let size = wholes.whole.as_ref().map(|w| w.size);
    let colour = wholes.colour.zip(size);
    put(
        &COLOUR,
        key.clone(),
        colour.map(|(pixels, size)| SmallFrames { pixels, size }),
    );
    put(&WHOLE, key.clone(), wholes.whole);
    put(&SURVEY, key.clone(), wholes.survey);
    put(&LARGE, key, wholes.large);
}

/// `frames` of the file `key` into `slot`, in place of any other's (emptied where none).
fn put(slot: &Slot, key: Option<FileKey>, frames: Option<SmallFrames>) {
    *slot.lock().unwrap_or_else(|e| e.into_inner()) = frames.and_then(|f| Some((key?, f)));
}

/// The kept whole of `path` at the track's size, taken: handed back where `whole` (the whole
/// recording is asked for) at this `size`, else let go (the track asked for a part, `--start`
/// or `--end`: they will not be asked for); none where another file's are kept, or the file
/// changed since.
pub(super) fn whole(path: &Path, size: (usize, usize), whole: bool) -> Option<SmallFrames> {
    whole_from(&WHOLE, path, size, whole)
}

/// The kept whole of `path` at the survey's size, as [`whole`] hands out the track's.
pub(super) fn surveyed(path: &Path, size: (usize, usize), whole: bool) -> Option<SmallFrames> {
    whole_from(&SURVEY, path, size, whole)
}

/// The kept whole of `path` at the track's size in colour, each frame's YUV 4:4:4 planes in
/// turn, as [`whole`] hands out the grey.
pub(super) fn colour(path: &Path, size: (usize, usize), whole: bool) -> Option<Vec<u8>> {
    whole_from(&COLOUR, path, size, whole).map(|f| f.pixels)
}

/// [`whole`] from `slot`.
fn whole_from(slot: &Slot, path: &Path, size: (usize, usize), all: bool) -> Option<SmallFrames> {
    taken(slot, &FileKey::of(path)?).filter(|f| all && f.size == size)
}

/// The frames kept in `slot` for the file `key`, taken; none (and the slot left alone) where
/// they are another file's.
fn taken(slot: &Slot, key: &FileKey) -> Option<SmallFrames> {
    let mut slot = slot.lock().unwrap_or_else(|e| e.into_inner());
    match slot.as_ref() {
        Some((k, _)) if k == key => slot.take().map(|(_, f)| f),
        _ => None,
    }
}

/// The frames `decode` reads of the recording at `input` (probed as `info`, progressive) within
/// `opts`' trim, cropped to `crop` (in the displayed frame's pixels) and resized to `opts.size`,
/// from the kept whole at its own size (taken): where one is kept for the file and holds its
/// every frame. The frames and their count; none otherwise.
pub(super) fn served(
    input: &Path,
    info: &VideoInfo,
    opts: &VideoOptions,
    crop: Crop,
) -> Option<(Vec<f32>, usize)> {
    served_from(&LARGE, input, info, opts, crop)
}

/// [`served`] from `slot`.
fn served_from(
    slot: &Slot,
    input: &Path,
    info: &VideoInfo,
    opts: &VideoOptions,
    crop: Crop,
) -> Option<(Vec<f32>, usize)> {
    if info.filter().is_some() {
        return None;
    }
    let large = taken(slot, &FileKey::of(input)?)?;
    if large.len() != info.frame_times.len() || large.size != (info.width, info.height) {
        return None;
    }
    // The frames ffmpeg keeps of a trim: those whose times lie within it (`times_within`).
    let t0 = info.frame_times.first().copied().unwrap_or(0.0);
    let (lo, hi) = (
        t0 + opts.start.unwrap_or(0.0),
        opts.end.map_or(f64::INFINITY, |e| t0 + e),
    );
    let mut resizer = FrameResizer::new(info.width, crop, opts.size);
    let mut frames = Vec::new();
    let mut count = 0;
    for (i, &t) in info.frame_times.iter().enumerate() {
        if t >= lo - 1e-6 && t < hi {
            frames.extend(resizer.resize(large.frame(i)));
            count += 1;
        }
    }
    Some((frames, count))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames(n: usize, size: (usize, usize)) -> SmallFrames {
        SmallFrames {
            pixels: (0..n * size.0 * size.1).map(|i| (i % 251) as u8).collect(),
            size,
        }
    }

    #[test]
    fn kept_frames_go_to_the_whole_asked_once_and_are_let_go_for_a_part() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.mp4"), dir.path().join("b.mp4"));
        std::fs::write(&a, b"a").unwrap();
        std::fs::write(&b, b"bb").unwrap();
        // A slot of the test's own: the process's are other tests' too.
        let slot: Slot = Mutex::new(None);
        let ka = FileKey::of(&a);
        // The whole, at its size: handed back, once; not to another file.
        put(&slot, ka.clone(), Some(frames(2, (4, 3))));
        assert!(
            whole_from(&slot, &b, (4, 3), true).is_none(),
            "another file's"
        );
        assert_eq!(
            whole_from(&slot, &a, (4, 3), true).map(|f| f.len()),
            Some(2)
        );
        assert!(
            whole_from(&slot, &a, (4, 3), true).is_none(),
            "handed out once"
        );
        // A part of it, or another size: not handed back, and not held any longer.
        for (size, all) in [((4, 3), false), ((8, 6), true)] {
            put(&slot, ka.clone(), Some(frames(2, (4, 3))));
            assert!(whole_from(&slot, &a, size, all).is_none());
            assert!(whole_from(&slot, &a, (4, 3), true).is_none());
        }
    }

    #[test]
    fn the_frames_served_are_the_trims_cropped_and_resized() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.mp4");
        std::fs::write(&file, b"a").unwrap();
        let info = VideoInfo {
            width: 8,
            height: 6,
            container_fps: Some(10.0),
            capture_fps: None,
            rotation: 0,
            expected_frames: Some(5),
            fields: None,
            frame_times: vec![1.0, 1.1, 1.2, 1.3, 1.4],
        };
        let opts = VideoOptions {
            fps: Some(10.0),
            crop: None,
            start: Some(0.1),
            end: Some(0.35),
            size: (4, 3),
            frames_per_clip: 2,
            stride: 1,
            hop: None,
            max_clips: 10,
        };
        let crop = Crop {
            x: 2,
            y: 1,
            w: 4,
            h: 3,
        };
        let kept = frames(5, (8, 6));
        let expected: Vec<f32> = (1..4)
            .flat_map(|i| FrameResizer::new(8, crop, (4, 3)).resize(kept.frame(i)))
            .collect();
        let slot: Slot = Mutex::new(None);
        put(&slot, FileKey::of(&file), Some(kept));
        let (got, count) = served_from(&slot, &file, &info, &opts, crop).expect("served");
        assert_eq!(count, 3, "the frames at 0.1, 0.2 and 0.3 s");
        assert_eq!(got, expected);
        assert!(
            served_from(&slot, &file, &info, &opts, crop).is_none(),
            "taken once"
        );
        // Frames of another size, or not every frame: decoded from the file.
        for other in [frames(5, (4, 3)), frames(4, (8, 6))] {
            put(&slot, FileKey::of(&file), Some(other));
            assert!(served_from(&slot, &file, &info, &opts, crop).is_none());
        }
    }
}
