//! Real recordings in: probe a video (or a folder of images) with ffprobe, decode it to grey
//! frames with the ffmpeg command-line tool, one frame at a time, crop and area-resize each in
//! Rust (the same code for videos and image folders), and cut the frames into clips.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What can go wrong reading a recording; every message names the input and the fix.
#[derive(Debug, thiserror::Error)]
pub enum VideoError {
    #[error("{tool} was not found on PATH: install ffmpeg (Debian/Ubuntu: apt-get install ffmpeg; macOS: brew install ffmpeg), which provides ffmpeg and ffprobe")]
    ToolMissing { tool: &'static str },
    #[error("{path}: not a readable video ({reason})")]
    NotAVideo { path: PathBuf, reason: String },
    #[error("{path}: {reason}")]
    BadInput { path: PathBuf, reason: String },
}

fn bad(path: &Path, reason: impl Into<String>) -> VideoError {
    VideoError::BadInput {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// A crop rectangle in pixels of the displayed (rotated) frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Crop {
    pub x: usize,
    pub y: usize,
    pub w: usize,
    pub h: usize,
}

/// How to turn a recording into clips.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct VideoOptions {
    /// Frames per second of real time; overrides the container's (slow-motion files).
    pub fps: Option<f64>,
    pub crop: Option<Crop>,
    /// Trim, in seconds of the file's own timeline (as a player shows it).
    pub start: Option<f64>,
    pub end: Option<f64>,
    /// Output frame size (width, height).
    pub size: (usize, usize),
    pub frames_per_clip: usize,
    /// Recording frames between consecutive clip frames (dt = stride / fps).
    pub stride: usize,
    /// Recording frames between the starts of consecutive clips; `None`: 1, or more so that at
    /// most `max_clips` clips result.
    pub hop: Option<usize>,
    pub max_clips: usize,
}

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
    /// Frames the container says it holds (nb_frames, or duration × fps), when it says.
    pub expected_frames: Option<usize>,
}

/// A decoded recording: every kept frame, resized, and the clips cut from it.
#[derive(Debug, Clone)]
pub struct DecodedVideo {
    pub info: VideoInfo,
    /// The frame rate used (the --fps override or the container's).
    pub fps: f64,
    /// All frames after trimming, [F, H·W] row-major, values in [0, 1].
    pub frames: Vec<f32>,
    /// F.
    pub frame_count: usize,
    /// First recording frame (index into `frames`) of each clip.
    pub clip_starts: Vec<usize>,
    /// Frames between clip starts.
    pub hop: usize,
    pub size: (usize, usize),
}

impl DecodedVideo {
    /// Seconds between clip frames.
    pub fn dt(&self, stride: usize) -> f64 {
        stride as f64 / self.fps
    }

    /// Recording frame index of every clip frame, [N·T] (clip-major): the clips are
    /// `frames[index]`, so they need not be copied out.
    pub fn clip_index(&self, frames_per_clip: usize, stride: usize) -> Vec<i64> {
        self.clip_starts
            .iter()
            .flat_map(|&s| (0..frames_per_clip).map(move |k| (s + k * stride) as i64))
            .collect()
    }

    /// The clips `which` (indices into `clip_starts`) as one [n, T, 1, H, W] array.
    pub fn clips(
        &self,
        which: &[usize],
        frames_per_clip: usize,
        stride: usize,
    ) -> (Vec<f32>, [usize; 5]) {
        let (w, h) = self.size;
        let mut out = Vec::with_capacity(which.len() * frames_per_clip * w * h);
        for &c in which {
            for k in 0..frames_per_clip {
                let f = self.clip_starts[c] + k * stride;
                out.extend_from_slice(&self.frames[f * w * h..(f + 1) * w * h]);
            }
        }
        (out, [which.len(), frames_per_clip, 1, h, w])
    }
}

/// Whether `path` is an input this module reads: a file that is not `.npy`, or a directory
/// that is not a dataset (no `frames.npy`, no `meta.json`, no `.partial` files), taken as a
/// folder of images.
pub fn is_recording(path: &Path) -> bool {
    if path.is_dir() {
        let dataset_like = std::fs::read_dir(path).is_ok_and(|mut d| {
            d.any(|e| {
                e.is_ok_and(|e| {
                    let name = e.file_name().to_string_lossy().into_owned();
                    name.starts_with("frames.npy")
                        || name.starts_with("meta.json")
                        || name.ends_with(".partial")
                })
            })
        });
        !dataset_like
    } else {
        path.extension()
            .is_none_or(|e| !e.eq_ignore_ascii_case("npy"))
    }
}

fn tool(name: &'static str) -> Result<Command, VideoError> {
    match Command::new(name)
        .arg("-version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
    {
        Ok(_) => Ok(Command::new(name)),
        Err(_) => Err(VideoError::ToolMissing { tool: name }),
    }
}

/// Image files (png, jpg, jpeg) in `dir`, in natural order (frame2 before frame10).
pub fn image_files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.is_file()
                && p.extension().is_some_and(|e| {
                    ["png", "jpg", "jpeg"]
                        .iter()
                        .any(|x| e.eq_ignore_ascii_case(x))
                })
        })
        .collect();
    files.sort_by(|a, b| natural_cmp(&a.to_string_lossy(), &b.to_string_lossy()));
    Ok(files)
}

/// Compares strings with runs of digits compared as numbers.
pub fn natural_cmp(a: &str, b: &str) -> std::cmp::Ordering {
    let (mut a, mut b) = (a, b);
    loop {
        match (a.chars().next(), b.chars().next()) {
            (None, None) => return std::cmp::Ordering::Equal,
            (None, _) => return std::cmp::Ordering::Less,
            (_, None) => return std::cmp::Ordering::Greater,
            (Some(x), Some(y)) if x.is_ascii_digit() && y.is_ascii_digit() => {
                let da = a.len() - a.trim_start_matches(|c: char| c.is_ascii_digit()).len();
                let db = b.len() - b.trim_start_matches(|c: char| c.is_ascii_digit()).len();
                let (na, nb) = (
                    a[..da].trim_start_matches('0'),
                    b[..db].trim_start_matches('0'),
                );
                let ord = na.len().cmp(&nb.len()).then_with(|| na.cmp(nb));
                if ord != std::cmp::Ordering::Equal {
                    return ord;
                }
                (a, b) = (&a[da..], &b[db..]);
            }
            (Some(x), Some(y)) => {
                if x != y {
                    return x.cmp(&y);
                }
                (a, b) = (&a[x.len_utf8()..], &b[y.len_utf8()..]);
            }
        }
    }
}

fn parse_rate(text: &str) -> Option<f64> {
    let (n, d) = text.split_once('/').unwrap_or((text, "1"));
    let (n, d) = (n.trim().parse::<f64>().ok()?, d.trim().parse::<f64>().ok()?);
    (d != 0.0 && n > 0.0).then(|| n / d)
}

/// Probes the first video stream of `path` with ffprobe.
pub fn probe(path: &Path) -> Result<VideoInfo, VideoError> {
    let out = tool("ffprobe")?
        .args([
            "-v",
            "error",
            "-print_format",
            "json",
            "-show_streams",
            "-show_format",
        ])
        .arg(path)
        .output()
        .map_err(|e| bad(path, format!("cannot run ffprobe: {e}")))?;
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
    Ok(VideoInfo {
        expected_frames,
        width: if quarter { h } else { w },
        height: if quarter { w } else { h },
        container_fps: fps,
        capture_fps,
        rotation,
    })
}

/// Area-average resampling weights: for each of `n_out` output cells over `n_in` inputs, the
/// (input index, weight) pairs, weights summing to 1.
fn area_weights(n_in: usize, n_out: usize) -> Vec<Vec<(usize, f32)>> {
    let scale = n_in as f64 / n_out as f64;
    (0..n_out)
        .map(|o| {
            let (a, b) = (o as f64 * scale, (o + 1) as f64 * scale);
            let mut w = Vec::new();
            let mut i = a.floor() as usize;
            while (i as f64) < b && i < n_in {
                let cover = (b.min(i as f64 + 1.0) - a.max(i as f64)).max(0.0);
                if cover > 0.0 {
                    w.push((i, (cover / scale) as f32));
                }
                i += 1;
            }
            w
        })
        .collect()
}

/// Crops a grey frame (`width` wide, bytes) and area-resizes it to `size`, values in [0, 1].
pub struct FrameResizer {
    crop: Crop,
    width: usize,
    cols: Vec<Vec<(usize, f32)>>,
    rows: Vec<Vec<(usize, f32)>>,
    row_buf: Vec<f32>,
}

impl FrameResizer {
    pub fn new(width: usize, crop: Crop, size: (usize, usize)) -> FrameResizer {
        FrameResizer {
            crop,
            width,
            cols: area_weights(crop.w, size.0),
            rows: area_weights(crop.h, size.1),
            row_buf: vec![0.0; crop.h * size.0],
        }
    }

    pub fn resize(&mut self, grey: &[u8]) -> Vec<f32> {
        let (cw, ch, ow) = (self.crop.w, self.crop.h, self.cols.len());
        for y in 0..ch {
            let row = &grey[(self.crop.y + y) * self.width + self.crop.x..][..cw];
            for (o, ws) in self.cols.iter().enumerate() {
                self.row_buf[y * ow + o] = ws.iter().map(|&(i, w)| row[i] as f32 * w).sum();
            }
        }
        let mut out = vec![0.0f32; self.rows.len() * ow];
        for (oy, ws) in self.rows.iter().enumerate() {
            for &(iy, w) in ws {
                for ox in 0..ow {
                    out[oy * ow + ox] += self.row_buf[iy * ow + ox] * w;
                }
            }
        }
        out.iter_mut()
            .for_each(|v| *v = (*v / 255.0).clamp(0.0, 1.0));
        out
    }
}

/// Decodes `input` (a video file, or a folder of images with `opts.fps`) into frames and clips.
/// Frames stream through a pipe one at a time; only the resized ones are kept.
pub fn decode(input: &Path, opts: &VideoOptions) -> Result<DecodedVideo, VideoError> {
    let folder = input.is_dir();
    let mut cmd = tool("ffmpeg")?;
    cmd.args(["-v", "error", "-nostdin"]);
    let mut list_file = None;
    let info = if folder {
        let files = image_files(input).map_err(|e| bad(input, format!("cannot list: {e}")))?;
        let first = files
            .first()
            .ok_or_else(|| bad(input, "holds no .png, .jpg or .jpeg images"))?;
        if opts.fps.is_none() {
            return Err(bad(
                input,
                "an image folder has no frame rate: pass --fps (frames per second of real time)",
            ));
        }
        if opts.start.is_some() || opts.end.is_some() {
            return Err(bad(
                input,
                "--start/--end trim videos; for an image folder, remove the unwanted images",
            ));
        }
        let mut info = probe(first)?;
        info.container_fps = None;
        info.expected_frames = Some(files.len());
        let mut text = String::from("ffconcat version 1.0\n");
        for f in &files {
            let abs = std::fs::canonicalize(f).map_err(|e| bad(f, e.to_string()))?;
            text += &format!("file '{}'\n", abs.to_string_lossy().replace('\'', "'\\''"));
        }
        let tmp = tempfile_path();
        std::fs::write(&tmp, text).map_err(|e| bad(&tmp, e.to_string()))?;
        cmd.args(["-f", "concat", "-safe", "0", "-i"]).arg(&tmp);
        list_file = Some(TempFile(tmp));
        info
    } else {
        if !input.exists() {
            return Err(bad(input, "no such file"));
        }
        let info = probe(input)?;
        if let Some(s) = opts.start {
            cmd.args(["-ss", &format!("{s}")]);
        }
        cmd.arg("-i").arg(input);
        if let Some(e) = opts.end {
            cmd.args(["-t", &format!("{}", e - opts.start.unwrap_or(0.0))]);
        }
        info
    };
    let fps = opts
        .fps
        .or(info.container_fps)
        .ok_or_else(|| bad(input, "the container gives no frame rate: pass --fps"))?;
    let crop = opts.crop.unwrap_or(Crop {
        x: 0,
        y: 0,
        w: info.width,
        h: info.height,
    });
    if crop.w == 0 || crop.h == 0 || crop.x + crop.w > info.width || crop.y + crop.h > info.height {
        return Err(bad(
            input,
            format!(
                "--crop {},{},{},{} lies outside the {}×{} frame (after rotation)",
                crop.x, crop.y, crop.w, crop.h, info.width, info.height
            ),
        ));
    }
    cmd.args([
        "-map",
        "0:v:0",
        "-fps_mode",
        "passthrough",
        "-f",
        "rawvideo",
        "-pix_fmt",
        "gray",
        "-",
    ]);
    cmd.stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(Stdio::null());
    let mut child = cmd
        .spawn()
        .map_err(|e| bad(input, format!("cannot run ffmpeg: {e}")))?;
    let mut stdout = child.stdout.take().expect("piped stdout");
    let mut stderr = child.stderr.take().expect("piped stderr");
    let err_reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = stderr.read_to_string(&mut s);
        s
    });
    let frame_bytes = info.width * info.height;
    let mut buf = vec![0u8; frame_bytes];
    let mut resizer = FrameResizer::new(info.width, crop, opts.size);
    let mut frames = Vec::new();
    let mut count = 0usize;
    let mut partial = false;
    loop {
        match read_full(&mut stdout, &mut buf) {
            Ok(n) if n == frame_bytes => {
                frames.extend(resizer.resize(&buf));
                count += 1;
            }
            Ok(0) => break,
            Ok(_) => {
                partial = true;
                break;
            }
            Err(e) => return Err(bad(input, format!("reading ffmpeg's output: {e}"))),
        }
    }
    let status = child.wait().map_err(|e| bad(input, e.to_string()))?;
    let log = err_reader.join().unwrap_or_default();
    drop(list_file);
    if !status.success() || partial {
        let line = log
            .lines()
            .last()
            .unwrap_or("decoding failed")
            .trim()
            .to_string();
        if count == 0 {
            return Err(VideoError::NotAVideo {
                path: input.to_path_buf(),
                reason: line,
            });
        }
        return Err(bad(
            input,
            format!(
                "decoding stopped after {} frames: {line} (a truncated file?)",
                count
            ),
        ));
    }
    let untrimmed = opts.start.is_none() && opts.end.is_none() && !folder;
    if let Some(expected) = info.expected_frames.filter(|_| untrimmed) {
        if !count == 0 && (count as f64) < 0.95 * expected as f64 {
            return Err(bad(
                input,
                format!(
                    "decoding stopped after {} of the {expected} frames the container announces (a truncated file?)",
                    count
                ),
            ));
        }
    }
    if count == 0 {
        return Err(bad(
            input,
            match (opts.start, opts.end) {
                (None, None) => "no frames decoded".to_string(),
                _ => format!(
                    "no frames between --start {} and --end {}",
                    opts.start.unwrap_or(0.0),
                    opts.end.map_or("the end".into(), |e| e.to_string())
                ),
            },
        ));
    }
    let span = (opts.frames_per_clip - 1) * opts.stride;
    if count <= span {
        return Err(bad(
            input,
            format!(
                "{} frames decoded, but one clip of {} frames at stride {} needs {}: lower --frames-per-clip or --stride, or trim less",
                count,
                opts.frames_per_clip,
                opts.stride,
                span + 1
            ),
        ));
    }
    let possible = count - span;
    let hop = opts
        .hop
        .unwrap_or_else(|| possible.div_ceil(opts.max_clips.max(1)).max(1));
    let clip_starts: Vec<usize> = (0..possible).step_by(hop).collect();
    Ok(DecodedVideo {
        info,
        fps,
        frames,
        frame_count: count,
        clip_starts,
        hop,
        size: opts.size,
    })
}

/// Reads until `buf` is full or the stream ends; returns the bytes read.
fn read_full(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut n = 0;
    while n < buf.len() {
        match r.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}

/// A file removed when dropped.
struct TempFile(PathBuf);

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

fn tempfile_path() -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    std::env::temp_dir().join(format!(
        "physvid-frames-{}-{}.ffconcat",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn natural_order_sorts_numbers_by_value() {
        let mut v = vec!["f10.png", "f2.png", "f1.png", "f02b.png", "g.png"];
        v.sort_by(|a, b| natural_cmp(a, b));
        assert_eq!(v, ["f1.png", "f2.png", "f02b.png", "f10.png", "g.png"]);
    }

    #[test]
    fn area_resize_averages_and_keeps_a_constant_image_constant() {
        let grey = vec![200u8; 7 * 5];
        let mut r = FrameResizer::new(
            7,
            Crop {
                x: 0,
                y: 0,
                w: 7,
                h: 5,
            },
            (3, 2),
        );
        let out = r.resize(&grey);
        assert!(
            out.iter().all(|v| (v - 200.0 / 255.0).abs() < 1e-5),
            "{out:?}"
        );
        // A 4×2 crop of a ramp halved in width: each output is the mean of two inputs.
        let ramp: Vec<u8> = (0..4 * 2).map(|i| (i * 10) as u8).collect();
        let mut r = FrameResizer::new(
            4,
            Crop {
                x: 0,
                y: 0,
                w: 4,
                h: 2,
            },
            (2, 1),
        );
        let out = r.resize(&ramp);
        let expect = [
            (0.0 + 10.0 + 40.0 + 50.0) / 4.0,
            (20.0 + 30.0 + 60.0 + 70.0) / 4.0,
        ];
        for (o, e) in out.iter().zip(expect) {
            assert!((o - e / 255.0).abs() < 1e-5, "{out:?}");
        }
    }

    #[test]
    fn rates_parse_as_fractions() {
        assert_eq!(
            parse_rate("30000/1001").map(|r| (r * 1000.0).round()),
            Some(29970.0)
        );
        assert_eq!(parse_rate("0/0"), None);
        assert_eq!(parse_rate("60"), Some(60.0));
    }
}
