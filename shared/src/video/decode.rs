//! `decode`: ffmpeg → grey frames through a pipe, one at a time, each resized as it arrives;
//! image folders go through ffmpeg's concat demuxer so both inputs take the same path. Checks
//! the crop, truncated or damaged files (any ffmpeg error), empty trims and clips that do not fit.

use super::folder::{concat_list, damaged_folder};
use super::probe::tool;
use super::{bad, image_files, probe, Crop, FrameResizer, VideoError, VideoInfo, VideoOptions};
use std::io::{BufRead, Read};
use std::path::Path;
use std::process::Stdio;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// A decoded recording: every kept frame, resized, and the clips cut from it.
#[derive(Debug, Clone)]
pub struct DecodedVideo {
    pub info: VideoInfo,
    /// The frame rate used (the --fps override or the container's).
    pub fps: f64,
    /// All frames after trimming, [F, H·W] row-major, values in [0, 1].
    pub frames: Vec<f32>,
    /// First recording frame (index into `frames`) of each clip.
    pub clip_starts: Vec<usize>,
    /// Frames between clip starts.
    pub hop: usize,
    pub size: (usize, usize),
}

impl DecodedVideo {
    /// Frames decoded (after trimming).
    pub fn frame_count(&self) -> usize {
        self.frames.len() / (self.size.0 * self.size.1)
    }

    /// Keeps frames `first..=last` only and cuts the clips of `opts` again from them.
    pub fn keep(&mut self, first: usize, last: usize, opts: &VideoOptions) {
        let per = self.size.0 * self.size.1;
        let last = last.min(self.frame_count().saturating_sub(1));
        self.frames.truncate((last + 1) * per);
        self.frames.drain(..first.min(last) * per);
        let span = (opts.frames_per_clip - 1).saturating_mul(opts.stride);
        (self.clip_starts, self.hop) = cut(self.frame_count(), span, opts);
    }

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

/// Decodes `input` (a video file, or a folder of images with `opts.fps`) into frames and clips.
/// Frames stream through a pipe one at a time; only the resized ones are kept. `probed`: the
/// video's [`probe`], when the caller already has it (it is probed otherwise).
pub fn decode(
    input: &Path,
    opts: &VideoOptions,
    probed: Option<VideoInfo>,
) -> Result<DecodedVideo, VideoError> {
    let folder = input.is_dir();
    let mut cmd = tool("ffmpeg")?;
    cmd.args(["-v", "error", "-nostdin"]);
    let mut list_file = None;
    let mut folder_files = Vec::new();
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
        info.frame_times = Vec::new();
        info.expected_frames = Some(files.len());
        let list = concat_list(&files)?;
        cmd.args(["-f", "concat", "-safe", "0", "-i"]).arg(&list.0);
        list_file = Some(list);
        folder_files = files;
        info
    } else {
        if !input.exists() {
            return Err(bad(input, "no such file"));
        }
        let info = match probed {
            Some(info) => info,
            None => probe(input)?,
        };
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
    // ffmpeg's complaints (at `-v error` a clean file has none), each with the frames read
    // when it came: damage in the middle of a file is reported near where it is.
    let progress = Arc::new(AtomicUsize::new(0));
    let seen = Arc::clone(&progress);
    let err_reader = std::thread::spawn(move || {
        std::io::BufReader::new(&mut stderr)
            .lines()
            .map_while(Result::ok)
            .map(|l| {
                (
                    seen.load(Ordering::Relaxed),
                    without_context(&l).to_string(),
                )
            })
            .filter(|(_, l)| !l.is_empty() && !l.starts_with("Last message repeated"))
            .collect::<Vec<_>>()
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
                progress.store(count, Ordering::Relaxed);
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
    let last = log.last().map_or("decoding failed", |(_, l)| l.as_str());
    if folder && (!log.is_empty() || !status.success() || count != folder_files.len()) {
        return Err(damaged_folder(input, &folder_files, count, last));
    }
    if count == 0 && (!status.success() || partial) {
        return Err(VideoError::NotAVideo {
            path: input.to_path_buf(),
            reason: last.to_string(),
        });
    }
    // Damage is judged by the frames the container's index holds (their timestamps), not by a
    // header's frame count: phone files announce frames they never had.
    let indexed = info.frames_within(opts.start, opts.end).unwrap_or(0);
    if indexed > 0 && count > 0 && (count as f64) < 0.95 * indexed as f64 {
        return Err(bad(
            input,
            format!(
                "decoding stopped after {count} of the {indexed} frames the container's index \
                 holds (a truncated or damaged file){}",
                log.first().map_or(String::new(), |(at, l)| format!(
                    "; ffmpeg's first error came near frame {at}: {l}"
                ))
            ),
        ));
    }
    if !status.success() || partial {
        return Err(bad(
            input,
            format!("decoding stopped after {count} frames: {last} (a truncated file?)"),
        ));
    }
    if let Some((at, first)) = log.first() {
        return Err(bad(
            input,
            format!(
                "damaged: ffmpeg reported {} decoding error(s), the first near frame {at} of \
                 {count} ({first}); re-encode the file, or keep an undamaged part with \
                 --start/--end",
                log.len()
            ),
        ));
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
    let span = (opts.frames_per_clip - 1).saturating_mul(opts.stride);
    if count <= span {
        return Err(bad(
            input,
            format!(
                "{} frames decoded, but one clip of {} frames at stride {} needs {}: lower --frames-per-clip or --stride, or trim less",
                count,
                opts.frames_per_clip,
                opts.stride,
                span.saturating_add(1)
            ),
        ));
    }
    let (clip_starts, hop) = cut(count, span, opts);
    Ok(DecodedVideo {
        info,
        fps,
        frames,
        clip_starts,
        hop,
        size: opts.size,
    })
}

/// Clip starts over `count` frames for clips spanning `span` frames, and the hop between
/// them (`opts.hop`, or as small as keeps within `opts.max_clips`).
fn cut(count: usize, span: usize, opts: &VideoOptions) -> (Vec<usize>, usize) {
    let possible = count.saturating_sub(span);
    let hop = opts
        .hop
        .unwrap_or_else(|| possible.div_ceil(opts.max_clips.max(1)).max(1));
    ((0..possible).step_by(hop).collect(), hop)
}

/// Reads until `buf` is full or the stream ends; returns the bytes read.
pub(super) fn read_full(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
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

/// An ffmpeg log line without its `[h264 @ 0x55…] ` context prefix.
fn without_context(line: &str) -> &str {
    let line = line.trim();
    match line.split_once("] ") {
        Some((ctx, rest)) if ctx.starts_with('[') && ctx.contains(" @ ") => rest,
        _ => line,
    }
}
