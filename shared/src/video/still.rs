//! One frame of a recording as a person sees it (rotated as the player shows it), as a JPEG no
//! larger than a page needs: the picture report.html draws a `--stick` on, and on which two
//! clicks give one.

use super::tools::tool;
use super::{bad, VideoError};
use std::path::Path;
use std::process::Stdio;

/// The longest side of the picture written (pixels): a page's width; clicks on it are read in
/// the frame's own pixels whatever its size here.
pub const LONGEST: u32 = 960;

/// The frame of `input` (a video file, or a folder of images) shown at `at` seconds of its
/// timeline (a folder: the image `at · fps` from its first), as JPEG bytes.
pub fn still(input: &Path, at: f64, fps: f64) -> Result<Vec<u8>, VideoError> {
    let mut cmd = tool("ffmpeg")?;
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
        .map_err(|e| bad(input, format!("ffmpeg did not run: {e}")))?;
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
