//! Running the ffmpeg tools: finding them on PATH, and reading their raw output a frame at a
//! time.

use super::{bad, VideoError};
use std::io::Read;
use std::path::Path;
use std::process::{Child, ChildStdout, Command, Stdio};

/// `name` (ffmpeg, ffprobe) as a command. Whether it is installed is learnt when it is started
/// ([`not_started`]), not asked beforehand: `name -version` cost a tenth of a second a tool,
/// a run on a recording's time as long as its whole decode on a short one.
pub(crate) fn tool(name: &'static str) -> Command {
    Command::new(name)
}

/// Why `tool` could not be started on `input`: not installed (the error that says how to
/// install it), or the reason the system gave.
pub(crate) fn not_started(tool: &'static str, input: &Path, e: std::io::Error) -> VideoError {
    match e.kind() {
        std::io::ErrorKind::NotFound => VideoError::ToolMissing { tool },
        _ => bad(input, format!("cannot run {tool}: {e}")),
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

/// Runs ffmpeg's `cmd` (its input and filters given) with raw frames in its pixel format
/// `pix_fmt` to a pipe, its complaints to `complaints`: the child and its output, or the error
/// naming `input`.
pub(crate) fn raw_frames(
    mut cmd: Command,
    input: &Path,
    pix_fmt: &str,
    complaints: Stdio,
) -> Result<(Child, ChildStdout), VideoError> {
    cmd.args(["-f", "rawvideo", "-pix_fmt", pix_fmt, "-"])
        .stdout(Stdio::piped())
        .stderr(complaints)
        .stdin(Stdio::null());
    let mut child = cmd.spawn().map_err(|e| not_started("ffmpeg", input, e))?;
    let stdout = child.stdout.take().expect("piped stdout");
    Ok((child, stdout))
}
