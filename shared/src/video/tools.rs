//! Running the ffmpeg tools: finding them on PATH, and reading their raw output a frame at a
//! time.

use super::{bad, VideoError};
use std::io::Read;
use std::path::Path;
use std::process::{Child, ChildStdout, Command, Stdio};
use std::sync::OnceLock;

/// `name` (ffmpeg, ffprobe) as a command, or the error that says how to install it. Whether
/// it runs is asked once a process (`name -version`: a twentieth of a second each time, eight
/// times in a run on a recording).
pub(crate) fn tool(name: &'static str) -> Result<Command, VideoError> {
    static FFMPEG: OnceLock<bool> = OnceLock::new();
    static FFPROBE: OnceLock<bool> = OnceLock::new();
    let runs = || {
        Command::new(name)
            .arg("-version")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok()
    };
    let runs = match name {
        "ffmpeg" => *FFMPEG.get_or_init(runs),
        "ffprobe" => *FFPROBE.get_or_init(runs),
        _ => runs(),
    };
    match runs {
        true => Ok(Command::new(name)),
        false => Err(VideoError::ToolMissing { tool: name }),
    }
}

/// Reads until `buf` is full or the stream ends; returns the bytes read.
pub(crate) fn read_full(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
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

/// `input` as ffmpeg's input, trimmed to `start`..`end` (s of its own timeline).
pub(crate) fn trimmed_input(cmd: &mut Command, input: &Path, start: Option<f64>, end: Option<f64>) {
    if let Some(s) = start {
        cmd.args(["-ss", &format!("{s}")]);
    }
    cmd.arg("-i").arg(input);
    if let Some(e) = end {
        cmd.args(["-t", &format!("{}", e - start.unwrap_or(0.0))]);
    }
}

/// ffmpeg's output arguments for every frame of the first video stream as it is, stamped on
/// the input's own time base (at the default 1/fps a variable-rate file's frames collide in
/// the output and ffmpeg complains about its own muxer).
pub(crate) const EVERY_FRAME: [&str; 6] = [
    "-map",
    "0:v:0",
    "-fps_mode",
    "passthrough",
    "-enc_time_base",
    "-1",
];

/// Runs ffmpeg's `cmd` (its input and filters given) with grey raw frames to a pipe, its
/// complaints dropped: the child and its output, or the error naming `input`.
pub(crate) fn gray_frames(cmd: Command, input: &Path) -> Result<(Child, ChildStdout), VideoError> {
    raw_frames(cmd, input, "gray")
}

/// As [`gray_frames`], in ffmpeg's pixel format `pix_fmt`.
pub(crate) fn raw_frames(
    mut cmd: Command,
    input: &Path,
    pix_fmt: &str,
) -> Result<(Child, ChildStdout), VideoError> {
    cmd.args(["-f", "rawvideo", "-pix_fmt", pix_fmt, "-"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .stdin(Stdio::null());
    let mut child = cmd
        .spawn()
        .map_err(|e| bad(input, format!("cannot run ffmpeg: {e}")))?;
    let stdout = child.stdout.take().expect("piped stdout");
    Ok((child, stdout))
}
