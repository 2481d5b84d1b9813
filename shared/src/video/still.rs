//! One frame of a recording as a person sees it (rotated as the player shows it), as a JPEG no
//! larger than a page needs: the picture report.html draws a `--stick` on, and on which two
//! clicks give one.

use super::tools::{not_started, tool};
use super::{bad, VideoError};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::sync::Mutex;
use std::thread::JoinHandle;

/// The longest side of the picture written (pixels): a page's width; clicks on it are read in
/// the frame's own pixels whatever its size here.
pub const LONGEST: u32 = 960;

/// A still being made before it is asked for ([`still_ahead`]): the file, the time (its
/// bits) and the thread making it. One at a time: a run shows one frame.
type Ahead = (PathBuf, u64, JoinHandle<Result<Vec<u8>, VideoError>>);
static AHEAD: Mutex<Option<Ahead>> = Mutex::new(None);

/// Starts making the still of the video file `input` at `at` s on a thread of its own, for
/// the [`still`] that will ask for it while the caller goes on (a run's training): a seek
/// into a 1080p recording and the decode to its frame take up to a second. A folder's
/// images are not made ahead.
pub fn still_ahead(input: &Path, at: f64) {
    if input.is_dir() {
        return;
    }
    let path = input.to_path_buf();
    let making = std::thread::spawn(move || made(&path, at, 0.0));
    *AHEAD.lock().unwrap_or_else(|e| e.into_inner()) =
        Some((input.to_path_buf(), at.to_bits(), making));
}

/// The frame of `input` (a video file, or a folder of images) shown at `at` seconds of its
/// timeline (a folder: the image `at · fps` from its first), as JPEG bytes: the one
/// [`still_ahead`] made, where it was asked for this one.
pub fn still(input: &Path, at: f64, fps: f64) -> Result<Vec<u8>, VideoError> {
    let ahead = {
        let mut ahead = AHEAD.lock().unwrap_or_else(|e| e.into_inner());
        match ahead.as_ref() {
            Some((p, t, _)) if p == input && *t == at.to_bits() => ahead.take(),
            _ => None,
        }
    };
    if let Some(Ok(made)) = ahead.map(|(_, _, making)| making.join()) {
        return made;
    }
    made(input, at, fps)
}

/// [`still`], made now.
fn made(input: &Path, at: f64, fps: f64) -> Result<Vec<u8>, VideoError> {
    let mut cmd = tool("ffmpeg");
    cmd.args(["-v", "error", "-nostdin"]);
    if input.is_dir() {
        let files =
            super::image_files(input).map_err(|e| bad(input, format!("cannot list: {e}")))?;
        let k = ((at * fps).round().max(0.0) as usize).min(files.len().saturating_sub(1));
        let file = files
            .get(k)
            .ok_or_else(|| bad(input, "no images to show"))?;
        cmd.arg("-i").arg(file);
    } else {
        cmd.args(["-ss", &format!("{:.6}", at.max(0.0))])
            .arg("-i")
            .arg(input);
    }
    let fit = format!(
        "scale='min({LONGEST},iw)':'min({LONGEST},ih)':force_original_aspect_ratio=decrease:\
         force_divisible_by=2,format=yuvj420p"
    );
    let out = cmd
        .args(["-frames:v", "1", "-vf", &fit])
        .args(["-f", "image2pipe", "-c:v", "mjpeg", "-q:v", "3", "-"])
        .stdin(Stdio::null())
        .output()
        .map_err(|e| not_started("ffmpeg", input, e))?;
    if !out.status.success() || out.stdout.is_empty() {
        return Err(bad(
            input,
            format!(
                "no frame at {at:.3} s: {}",
                String::from_utf8_lossy(&out.stderr).trim()
            ),
        ));
    }
    Ok(out.stdout)
}
