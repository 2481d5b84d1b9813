//! Running the ffmpeg tools: finding them on PATH, and reading their raw output a frame at a
//! time.

use super::{bad, VideoError};
use std::io::Read;
use std::path::Path;
use std::process::{Child, ChildStdout, Command, Stdio};

/// `name` (ffmpeg, ffprobe) as a command, or the error that says how to install it.
pub(crate) fn tool(name: &'static str) -> Result<Command, VideoError> {
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

/// Runs ffmpeg's `cmd` (its input and filters given) with grey raw frames to a pipe, its
/// complaints dropped: the child and its output, or the error naming `input`.
pub(crate) fn gray_frames(
    mut cmd: Command,
    input: &Path,
) -> Result<(Child, ChildStdout), VideoError> {
    cmd.args(["-f", "rawvideo", "-pix_fmt", "gray", "-"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .stdin(Stdio::null());
    let mut child = cmd
        .spawn()
        .map_err(|e| bad(input, format!("cannot run ffmpeg: {e}")))?;
    let stdout = child.stdout.take().expect("piped stdout");
    Ok((child, stdout))
}
