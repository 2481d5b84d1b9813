//! `decode`: ffmpeg → grey frames through a pipe, one at a time, each resized as it arrives;
//! image folders go through ffmpeg's concat demuxer so both inputs take the same path. Checks
//! the crop, truncated or damaged files (any ffmpeg error), empty trims and clips that do not
//! fit, and puts the frames on their own clock (`clock`).

use super::clock::Clock;
use super::decoded::{cut, DecodedVideo};
use super::folder::{check_alike, concat_list, damaged_folder, numbered};
use super::tools::{not_started, read_full, tool, trimmed_input, EVERY_FRAME};
use super::{bad, image_files, probe, Crop, FrameResizer, VideoError, VideoInfo, VideoOptions};
use std::io::BufRead;
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// Decodes `input` (a video file, or a folder of images with `opts.fps`) into frames and clips.
/// Frames stream through a pipe one at a time; only the resized ones are kept. `probed`: the
/// video's [`probe`], when the caller already has it (it is probed otherwise).
pub fn decode(
    input: &Path,
    opts: &VideoOptions,
    probed: Option<VideoInfo>,
) -> Result<DecodedVideo, VideoError> {
    let folder = input.is_dir();
    let mut cmd = tool("ffmpeg");
    cmd.args(["-v", "error", "-nostdin"]);
    let mut list_file = None;
    let mut folder_files = Vec::new();
    let info = if folder {
        let files = image_files(input).map_err(|e| bad(input, format!("cannot list: {e}")))?;
        let first = files
            .first()
            .ok_or_else(|| bad(input, "holds no .png, .jpg or .jpeg images"))?;
        check_alike(&files)?;
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
        info.fields = None;
        let list = concat_list(&files)?;
        cmd.args(["-f", "concat", "-safe", "0", "-i"])
            .arg(list.path());
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
        trimmed_input(&mut cmd, input, opts.start, opts.end);
        info
    };
    let fps = opts
        .fps
        .or(info.container_fps)
        .ok_or_else(|| bad(input, "the container gives no frame rate: pass --fps"))?;
    let crop = Crop::of(opts, &info);
    if crop.w == 0 || crop.h == 0 || crop.x + crop.w > info.width || crop.y + crop.h > info.height {
        return Err(bad(
            input,
            format!(
                "--crop {},{},{},{} lies outside the {}×{} frame (after rotation)",
                crop.x, crop.y, crop.w, crop.h, info.width, info.height
            ),
        ));
    }
    // The crop cut by ffmpeg (on the displayed picture, exactly: `exact` keeps an odd corner
    // where a subsampled chroma would round it), so that the pipe carries only the frames'
    // part kept: a tenth of a 1080p frame for an object's path.
    let whole = crop.x == 0 && crop.y == 0 && crop.w == info.width && crop.h == info.height;
    let cropped =
        (!whole).then(|| format!("crop={}:{}:{}:{}:exact=1", crop.w, crop.h, crop.x, crop.y));
    let filters: Vec<String> = info.filter().into_iter().chain(cropped).collect();
    if !filters.is_empty() {
        cmd.args(["-vf", &filters.join(",")]);
    }
    cmd.args(EVERY_FRAME)
        .args(["-f", "rawvideo", "-pix_fmt", "gray", "-"]);
    // The frames the look at the file's fields decoded beside it, where they serve (`kept`);
    // else ffmpeg's.
    let served = match folder {
        true => None,
        false => super::kept::served(input, &info, opts, crop),
    };
    let Pulled {
        mut frames,
        mut count,
        partial,
        success,
        log,
    } = match served {
        Some((frames, count)) => Pulled {
            frames,
            count,
            partial: false,
            success: true,
            log: Vec::new(),
        },
        None => pulled(cmd, input, crop, opts.size)?,
    };
    drop(list_file);
    let last = log.last().map_or("decoding failed", |(_, l)| l.as_str());
    if folder && (!log.is_empty() || !success || count != folder_files.len()) {
        return Err(damaged_folder(input, &folder_files, count, last));
    }
    if count == 0 && (!success || partial) {
        return Err(VideoError::NotAVideo {
            path: input.to_path_buf(),
            reason: last.to_string(),
        });
    }
    // Damage is judged by the frames the container's index holds (their timestamps), not by a
    // header's frame count: phone files announce frames they never had.
    // One frame at a boundary of a short span is ffmpeg's rounding of the times, not damage.
    let indexed = info.frames_within(opts.start, opts.end).unwrap_or(0);
    if indexed > 0 && count > 0 && ((count + 1) as f64) < 0.95 * indexed as f64 {
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
    if !success || partial {
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
    // The frames on their own clock: the container's timestamps, or the images' numbers.
    let times = if folder {
        numbered(&folder_files)
    } else {
        Some(info.times_within(opts.start, opts.end))
    };
    let per = opts.size.0 * opts.size.1;
    let (mut clock_note, mut timeline_fps, mut first_s) = (None, info.container_fps, 0.0);
    if let Some(times) = times.filter(|t| t.len() == count && count >= 2) {
        let clock = Clock::fit(&times).map_err(|u| match folder {
            false => bad(input, u.reason()),
            true => bad(
                input,
                format!(
                    "the images' numbers skip frames (the longest run missing: {}; at most {} \
                     in a row, and a tenth of all, are filled in): add the missing images or \
                     keep an evenly numbered part",
                    u.gap.map_or(0, |g| g.1),
                    super::clock::MAX_MISSING
                ),
            ),
        })?;
        if !folder && timeline_fps.is_none_or(|c| (c * clock.interval - 1.0).abs() > 1e-3) {
            timeline_fps = Some(1.0 / clock.interval);
        }
        if !clock.is_even() {
            frames = clock.resample(&times, &frames, per);
            count = frames.len() / per;
            first_s = times[clock.head] - times[0];
            clock_note = clock.note(!folder);
        }
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
        timeline_fps,
        clock_note,
        first_s,
    })
}

/// An ffmpeg log line without its `[h264 @ 0x55…] ` context prefix.
fn without_context(line: &str) -> &str {
    let line = line.trim();
    match line.split_once("] ") {
        Some((ctx, rest)) if ctx.starts_with('[') && ctx.contains(" @ ") => rest,
        _ => line,
    }
}

/// What ffmpeg gave: the frames resized, how many, whether the last was cut short, whether it
/// finished well, and its complaints (each with the frames read when it came).
struct Pulled {
    frames: Vec<f32>,
    count: usize,
    partial: bool,
    success: bool,
    log: Vec<(usize, String)>,
}

/// Runs ffmpeg's `cmd` (input, filters and raw grey output given) on `input`, each frame of
/// `crop`'s size resized to `size` as it arrives.
fn pulled(
    mut cmd: Command,
    input: &Path,
    crop: Crop,
    size: (usize, usize),
) -> Result<Pulled, VideoError> {
    cmd.stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .stdin(Stdio::null());
    let mut child = cmd.spawn().map_err(|e| not_started("ffmpeg", input, e))?;
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
            // Two frames with one timestamp (a doubled frame) trouble only the raw output's
            // muxer; the clock leaves one of them out.
            .filter(|(_, l)| !l.contains("non monotonically increasing dts to muxer"))
            .collect::<Vec<_>>()
    });
    let frame_bytes = crop.w * crop.h;
    let mut buf = vec![0u8; frame_bytes];
    let piped = Crop { x: 0, y: 0, ..crop };
    let mut resizer = FrameResizer::new(crop.w, piped, size);
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
    Ok(Pulled {
        frames,
        count,
        partial,
        success: status.success(),
        log: err_reader.join().unwrap_or_default(),
    })
}
