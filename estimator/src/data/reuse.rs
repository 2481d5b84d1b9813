//! One decode and one survey for every candidate of a model choice: the frames of the last
//! recording decoded by a candidate are kept, and a later candidate asking for the same frames
//! (file, frame rate, crop, trim and size: its clips may be cut otherwise) gets a copy, its
//! clips cut again; the last survey of where the picture moves (file and trim), the common
//! cut's or a candidate's, likewise. Measured on the shared pendulum recording: 1.9 s of
//! decoding per candidate; on the jar, 0.5 s of surveying.

use physvid_shared::video::{
    self, Crop, DecodedVideo, Survey, VideoError, VideoInfo, VideoOptions,
};
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

/// A file's length and modification time: a file rewritten in place is read again.
fn stamp(input: &Path) -> Option<(u64, std::time::SystemTime)> {
    std::fs::metadata(input)
        .ok()
        .and_then(|m| Some((m.len(), m.modified().ok()?)))
}

impl Key {
    fn of(input: &Path, opts: &VideoOptions) -> Key {
        Key {
            input: input.to_path_buf(),
            stamp: stamp(input),
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

/// What a survey depends on: the file, as probed (a recording read as its fields has other
/// frames), and the trim.
#[derive(Debug, Clone, PartialEq)]
struct SurveyKey {
    input: PathBuf,
    stamp: Option<(u64, std::time::SystemTime)>,
    info: VideoInfo,
    start: Option<u64>,
    end: Option<u64>,
}

impl SurveyKey {
    fn of(input: &Path, info: &VideoInfo, (start, end): (Option<f64>, Option<f64>)) -> SurveyKey {
        SurveyKey {
            input: input.to_path_buf(),
            stamp: stamp(input),
            info: info.clone(),
            start: start.map(f64::to_bits),
            end: end.map(f64::to_bits),
        }
    }
}

/// The last survey kept by [`survey`], and whether it measured the period.
static LAST_SURVEY: Mutex<Option<(SurveyKey, Survey, bool)>> = Mutex::new(None);

/// `video::survey`, kept for (and served from) the next call on the same file and trim when
/// `keep` (the common cut and the candidates of a model choice): a survey that measured the
/// period serves one that does not ask for it (the rest is the same pass).
pub fn survey(
    input: &Path,
    info: &VideoInfo,
    span: (Option<f64>, Option<f64>),
    period: bool,
    keep: bool,
) -> Result<Survey, VideoError> {
    if !keep {
        return video::survey(input, info, span, period);
    }
    let key = SurveyKey::of(input, info, span);
    let mut last = LAST_SURVEY.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((k, s, with_period)) = last.as_ref() {
        if *k == key && (*with_period || !period) {
            let mut s = s.clone();
            if !period {
                s.period_frames = None;
            }
            return Ok(s);
        }
    }
    let s = video::survey(input, info, span, period)?;
    *last = Some((key, s.clone(), period));
    Ok(s)
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

    #[test]
    fn a_survey_is_kept_for_the_same_file_as_probed_and_the_same_trim() {
        let info = VideoInfo {
            width: 64,
            height: 48,
            container_fps: Some(30.0),
            capture_fps: None,
            rotation: 0,
            expected_frames: Some(3),
            fields: None,
            frame_times: vec![0.0, 1.0 / 30.0, 2.0 / 30.0],
        };
        let p = Path::new("a.mp4");
        let key = SurveyKey::of(p, &info, (Some(0.5), None));
        assert_eq!(key, SurveyKey::of(p, &info, (Some(0.5), None)));
        assert_ne!(key, SurveyKey::of(p, &info, (Some(0.5), Some(2.0))));
        assert_ne!(
            key,
            SurveyKey::of(Path::new("b.mp4"), &info, (Some(0.5), None))
        );
        // Read as its fields: other frames.
        let fields = VideoInfo {
            frame_times: vec![0.0, 1.0 / 60.0, 2.0 / 60.0],
            ..info.clone()
        };
        assert_ne!(key, SurveyKey::of(p, &fields, (Some(0.5), None)));
    }
}
