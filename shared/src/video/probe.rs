//! `probe`: what ffprobe says about a recording (displayed size after the rotation tag, frame
//! rate, the slow-motion capture tag, frame count, interlacing).

use super::clock::{Clock, Uneven};
use super::fields::{self, Fields, FieldsChoice};
use super::tools::{not_started, tool};
use super::{bad, FileKey, VideoError};
use std::path::Path;
use std::sync::Mutex;

/// What ffprobe says about a recording.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct VideoInfo {
    /// Displayed size (after the rotation tag).
    pub width: usize,
    pub height: usize,
    /// The container's frame rate (None for image folders).
    pub container_fps: Option<f64>,
    /// `com.android.capture.fps`, when the file has it (slow-motion captures).
    pub capture_fps: Option<f64>,
    /// Rotation tag in degrees (0 when absent).
    pub rotation: i64,
    /// An interlaced recording's fields (`fields`): read as frames at twice the rate, so the
    /// rates, counts and times here are the fields'.
    pub fields: Option<Fields>,
    /// Frames the container says it holds (nb_frames, or duration × fps), when it says.
    pub expected_frames: Option<usize>,
    /// The frames' own presentation times (s, sorted), from the container's index without
    /// decoding; empty for image folders.
    #[serde(skip)]
    pub frame_times: Vec<f64>,
}

impl VideoInfo {
    /// The recording read as its `fields`: twice the frames, at twice the rate, each frame's
    /// time followed by its second field's.
    fn into_fields(self, fields: Fields) -> VideoInfo {
        VideoInfo {
            container_fps: self.container_fps.map(|f| 2.0 * f),
            capture_fps: self.capture_fps.map(|f| 2.0 * f),
            expected_frames: self.expected_frames.map(|n| 2 * n),
            frame_times: fields::times(&self.frame_times),
            fields: Some(fields),
            ..self
        }
    }

    /// The filter ffmpeg applies before anything else (an interlaced recording's fields made
    /// frames), when one is needed.
    pub fn filter(&self) -> Option<String> {
        self.fields.map(|f| f.filter())
    }

    /// Frames per second of what is read for `fps` frames per second of the recording (twice
    /// it for an interlaced one's fields).
    pub fn read_rate(&self, fps: f64) -> f64 {
        if self.fields.is_some() {
            2.0 * fps
        } else {
            fps
        }
    }

    /// The even clock the frames' timestamps within `start`..`end` (s) sit on, when the file
    /// gives at least two (`clock::Clock`), or why none fits.
    pub fn clock(&self, start: Option<f64>, end: Option<f64>) -> Option<Result<Clock, Uneven>> {
        let t = self.times_within(start, end);
        (t.len() >= 2).then(|| Clock::fit(&t))
    }

    /// The frames' timestamps within `start`..`end` (s from the first frame; the end excluded,
    /// as the decoder keeps them).
    pub fn times_within(&self, start: Option<f64>, end: Option<f64>) -> Vec<f64> {
        let (lo, hi) = self.bounds(start, end);
        self.frame_times
            .iter()
            .copied()
            .filter(|&t| t >= lo - 1e-6 && t < hi)
            .collect()
    }

    /// How many frames the container's index puts within `start`..`end` (s; the end excluded,
    /// as the decoder keeps them), when it gives timestamps.
    pub fn frames_within(&self, start: Option<f64>, end: Option<f64>) -> Option<usize> {
        self.frame_times.first()?;
        let (lo, hi) = self.bounds(start, end);
        Some(
            self.frame_times
                .iter()
                .filter(|&&t| t >= lo - 1e-6 && t < hi)
                .count(),
        )
    }

    /// `start`..`end` (s from the first frame) on the file's own timeline.
    fn bounds(&self, start: Option<f64>, end: Option<f64>) -> (f64, f64) {
        let t0 = self.frame_times.first().copied().unwrap_or(0.0);
        (
            t0 + start.unwrap_or(0.0),
            end.map_or(f64::INFINITY, |e| t0 + e),
        )
    }
}

fn parse_rate(text: &str) -> Option<f64> {
    let (n, d) = text.split_once('/').unwrap_or((text, "1"));
    let (n, d) = (n.trim().parse::<f64>().ok()?, d.trim().parse::<f64>().ok()?);
    (d != 0.0 && n > 0.0).then(|| n / d)
}

/// Probes the first video stream of `path` with ffprobe, its fields found (`fields`).
pub fn probe(path: &Path) -> Result<VideoInfo, VideoError> {
    probe_as(path, FieldsChoice::Auto)
}

/// How many files' probes a process keeps: a run reads one or two files; a Python session may
/// probe hundreds, whose frame times would otherwise pile up. Not a threshold on any recording.
const KEPT_PROBES: usize = 8;

/// As [`probe`], its fields read as `choice` says (`--fields`). One of the last
/// [`KEPT_PROBES`] files probed in this process, unchanged since (its size and modification
/// time), is not probed again (the track and the latent route each ask: an ffprobe run and a
/// look at its fields).
pub fn probe_as(path: &Path, choice: FieldsChoice) -> Result<VideoInfo, VideoError> {
    type Key = (FileKey, FieldsChoice);
    static PROBED: Mutex<Vec<(Key, VideoInfo)>> = Mutex::new(Vec::new());
    let key = FileKey::of(path).map(|f| (f, choice));
    let lock = || PROBED.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(k) = &key {
        if let Some((_, info)) = lock().iter().find(|(was, _)| was == k) {
            return Ok(info.clone());
        }
    }
    let info = probe_fresh(path, choice)?;
    if let Some(k) = key {
        let mut probed = lock();
        if probed.len() >= KEPT_PROBES {
            probed.remove(0);
        }
        probed.push((k, info.clone()));
    }
    Ok(info)
}

/// [`probe_as`] by ffprobe, every time.
fn probe_fresh(path: &Path, choice: FieldsChoice) -> Result<VideoInfo, VideoError> {
    crate::input::check_kind(path).map_err(|e| bad(path, e))?;
    let out = tool("ffprobe")
        .args([
            "-v",
            "error",
            "-print_format",
            "json",
            "-select_streams",
            "v:0",
            "-show_streams",
            "-show_format",
            "-show_entries",
            "packet=pts_time",
        ])
        .arg(path)
        .output()
        .map_err(|e| not_started("ffprobe", path, e))?;
    let not_video = |reason: String| VideoError::NotAVideo {
        path: path.to_path_buf(),
        reason,
    };
    if !out.status.success() {
        let msg = String::from_utf8_lossy(&out.stderr);
        let line = msg.lines().last().unwrap_or("ffprobe failed").trim();
        return Err(not_video(line.to_string()));
    }
    let v: serde_json::Value = serde_json::from_slice(&out.stdout)
        .map_err(|e| not_video(format!("ffprobe printed no JSON: {e}")))?;
    let stream = v["streams"]
        .as_array()
        .and_then(|s| s.iter().find(|s| s["codec_type"] == "video"))
        .ok_or_else(|| not_video("no video stream".into()))?;
    let dim = |k: &str| stream[k].as_u64().filter(|&d| d > 0).map(|d| d as usize);
    let (w, h) = dim("width")
        .zip(dim("height"))
        .ok_or_else(|| not_video("the video stream has no size".into()))?;
    let side_rotation = stream["side_data_list"].as_array().and_then(|l| {
        l.iter().find_map(|d| {
            d["rotation"]
                .as_f64()
                .or_else(|| d["rotation"].as_str()?.parse().ok())
        })
    });
    let tag_rotation = stream["tags"]["rotate"]
        .as_str()
        .and_then(|r| r.parse::<f64>().ok());
    let rotation = side_rotation.or(tag_rotation).unwrap_or(0.0).round() as i64;
    let quarter = rotation.rem_euclid(180) == 90;
    let fps = stream["avg_frame_rate"]
        .as_str()
        .and_then(parse_rate)
        .or_else(|| stream["r_frame_rate"].as_str().and_then(parse_rate));
    let capture_fps = v["format"]["tags"]["com.android.capture.fps"]
        .as_str()
        .or_else(|| stream["tags"]["com.android.capture.fps"].as_str())
        .and_then(|t| t.trim().parse::<f64>().ok())
        .filter(|f| *f > 0.0);
    let expected_frames = stream["nb_frames"]
        .as_str()
        .and_then(|n| n.parse::<usize>().ok())
        .or_else(|| {
            let d = stream["duration"]
                .as_str()
                .or_else(|| v["format"]["duration"].as_str())?
                .parse::<f64>()
                .ok()?;
            Some((d * fps?).round() as usize)
        })
        .filter(|&n| n > 0);
    let info = VideoInfo {
        frame_times: frame_times(&v),
        expected_frames,
        width: if quarter { h } else { w },
        height: if quarter { w } else { h },
        container_fps: fps,
        capture_fps,
        rotation,
        fields: None,
    };
    // Fields are rows as stored: a rotated recording (a phone's, never interlaced) is not
    // looked at, nor split.
    if rotation != 0 {
        return Ok(info);
    }
    let tag = stream["field_order"].as_str().and_then(fields::from_tag);
    let counted = info.expected_frames.or(Some(info.frame_times.len()));
    let found = match fields::chosen(choice) {
        Some(given) => given,
        None => fields::find(path, (w, h), counted, tag)?,
    };
    Ok(match found {
        Some(f) => info.into_fields(f),
        None => info,
    })
}

/// The presentation times of the first video stream's packets (s, sorted), as ffprobe read
/// them from the container's index without decoding (`packets` of its JSON).
fn frame_times(v: &serde_json::Value) -> Vec<f64> {
    let mut t: Vec<f64> = v["packets"]
        .as_array()
        .map(|ps| {
            ps.iter()
                .filter_map(|p| p["pts_time"].as_str()?.trim().parse::<f64>().ok())
                .filter(|t| t.is_finite())
                .collect()
        })
        .unwrap_or_default();
    t.sort_by(f64::total_cmp);
    presented(t)
}

/// The times of the frames a player shows: an edit list (a phone's trim, `ffmpeg -ss … -c copy`)
/// keeps the packets before the cut in the file, at negative times, to decode the first shown
/// frame; they are never presented, and counting them made a healthy file look truncated.
fn presented(times: Vec<f64>) -> Vec<f64> {
    if times.iter().any(|&t| t >= 0.0) {
        times.into_iter().filter(|&t| t >= 0.0).collect()
    } else {
        times
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_probed_again_is_read_again_once_it_changed() {
        let dir = std::env::temp_dir().join(format!("physvid-probe-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("clip.mp4");
        let render = |size: &str| {
            tool("ffmpeg")
                .args(["-v", "error", "-y", "-f", "lavfi", "-i"])
                .arg(format!("testsrc=size={size}:rate=10"))
                .args(["-frames:v", "5", "-pix_fmt", "yuv420p"])
                .arg(&file)
                .status()
                .ok()
                .filter(|s| s.success())
        };
        if render("32x24").is_none() {
            return; // no ffmpeg here
        }
        let first = probe(&file).unwrap();
        assert_eq!((first.width, first.height), (32, 24));
        // Unchanged: the same answer (from the process's record).
        assert_eq!(probe(&file).unwrap(), first);
        // Written again, another size: probed afresh.
        render("48x24").unwrap();
        assert_eq!(probe(&file).unwrap().width, 48);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn frames_before_an_edit_lists_cut_are_not_presented() {
        assert_eq!(presented(vec![-0.5, -0.1, 0.0, 0.1]), vec![0.0, 0.1]);
        assert_eq!(presented(vec![-0.2, -0.1]), vec![-0.2, -0.1]);
    }

    #[test]
    fn rates_parse_as_fractions() {
        assert_eq!(
            parse_rate("30000/1001").map(|r| (r * 1000.0).round()),
            Some(29970.0)
        );
        assert_eq!(parse_rate("0/0"), None);
        assert_eq!(parse_rate("60"), Some(60.0));
        let info = VideoInfo {
            width: 1,
            height: 1,
            container_fps: Some(10.0),
            capture_fps: None,
            rotation: 0,
            expected_frames: None,
            fields: None,
            frame_times: vec![0.0, 0.1, 0.2, 0.3, 0.9, 1.0, 1.1],
        };
        let e = info.clock(None, None).unwrap().unwrap_err();
        assert_eq!(e.gap.map(|g| g.1), Some(5), "{e:?}");
        let c = info.clock(Some(0.85), None).unwrap().unwrap();
        assert!(c.is_even() && (c.interval - 0.1).abs() < 1e-9, "{c:?}");
    }
}
