//! Real recordings in: probe a video (or a folder of images) with ffprobe, decode it to grey
//! frames with the ffmpeg command-line tool, one frame at a time, crop and area-resize each in
//! Rust (the same code for videos and image folders), and cut the frames into clips. This file:
//! the errors, the options, and what counts as a recording.

pub mod clock;
mod colour;
mod decode;
mod decoded;
pub mod fields;
mod folder;
pub mod free;
mod kept;
mod probe;
pub mod region;
mod resize;
mod small;
mod still;
mod survey;
pub mod timescale;
mod tools;

pub use colour::colour_frames;
pub use decode::decode;
pub use decoded::{DecodedVideo, SmallFrames};
pub use probe::{probe, probe_as, VideoInfo};
pub use resize::{shifted, FrameResizer};
pub use small::{small_chroma, small_frames, SURVEY_SIDE, TRACK_SIDE};
pub use still::{still, still_ahead};
pub use survey::{survey, MotionStats, Survey};

use std::path::{Path, PathBuf};

/// What can go wrong reading a recording; every message names the input and the fix.
#[derive(Debug, thiserror::Error)]
pub enum VideoError {
    #[error("{tool} was not found on PATH: install ffmpeg (Debian/Ubuntu: apt-get install ffmpeg; macOS: brew install ffmpeg), which provides ffmpeg and ffprobe")]
    ToolMissing { tool: &'static str },
    #[error("{path}: not a readable video ({reason})")]
    NotAVideo { path: PathBuf, reason: String },
    #[error("{path}: {reason}")]
    BadInput { path: PathBuf, reason: String },
    /// A temporary file could not be made (the system's temporary folder, TMPDIR, is full or
    /// unwritable): a failure of the machine, not of the input.
    #[error("cannot write a temporary file in {path} (the temporary folder; set TMPDIR to a writable one)")]
    Scratch {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
}

pub(crate) fn bad(path: &Path, reason: impl Into<String>) -> VideoError {
    VideoError::BadInput {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// A file as it is now: its canonical path, size and modification time (a file written again
/// is another), for what a process keeps of a file it read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FileKey(PathBuf, u64, Option<std::time::SystemTime>);

impl FileKey {
    /// `path`'s key, none where it cannot be read.
    pub(crate) fn of(path: &Path) -> Option<FileKey> {
        let m = std::fs::metadata(path).ok()?;
        let at = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        Some(FileKey(at, m.len(), m.modified().ok()))
    }
}

/// A crop rectangle in pixels of the displayed (rotated) frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Crop {
    pub x: usize,
    pub y: usize,
    pub w: usize,
    pub h: usize,
}

impl Crop {
    /// What `opts` crop of a frame of `info` (the whole frame without `--crop`).
    pub fn of(opts: &VideoOptions, info: &VideoInfo) -> Crop {
        opts.crop.unwrap_or(Crop {
            x: 0,
            y: 0,
            w: info.width,
            h: info.height,
        })
    }

    /// The crop widened (about its centre, within the `frame`'s width and height) to the
    /// aspect ratio `aspect` (width / height), so that resizing it to the encoder's frame
    /// magnifies both directions alike (a narrow band along a swing would otherwise be
    /// stretched across, and the bob's rise at the ends of its swing with it).
    pub fn with_aspect(self, aspect: f64, frame: (usize, usize)) -> Crop {
        let (fw, fh) = (frame.0 as f64, frame.1 as f64);
        let (mut w, mut h) = (self.w as f64, self.h as f64);
        if w / h < aspect {
            w = (h * aspect).min(fw);
        } else {
            h = (w / aspect).min(fh);
        }
        let (cx, cy) = (
            self.x as f64 + self.w as f64 / 2.0,
            self.y as f64 + self.h as f64 / 2.0,
        );
        let x = (cx - w / 2.0).clamp(0.0, fw - w);
        let y = (cy - h / 2.0).clamp(0.0, fh - h);
        Crop {
            x: x.round() as usize,
            y: y.round() as usize,
            w: (w.round() as usize).min(frame.0 - x.round() as usize),
            h: (h.round() as usize).min(frame.1 - y.round() as usize),
        }
    }

    /// Its share of a `frame` (w, h).
    pub fn area_share(&self, frame: (usize, usize)) -> f64 {
        (self.w * self.h) as f64 / (frame.0 * frame.1).max(1) as f64
    }
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

/// Whether `path` is an input this module reads: a file that is not `.npy` (by its name or its
/// first bytes), or a directory that is not a dataset (no `frames.npy`, no `meta.json`, no
/// `.partial` files), taken as a folder of images.
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
        let named_npy = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
        !named_npy && !starts_like_npy(path)
    }
}

/// Whether the file at `path` begins with the `.npy` magic string.
fn starts_like_npy(path: &Path) -> bool {
    use std::io::Read;
    let mut magic = [0u8; 6];
    // Only a regular file is opened: a FIFO would block here.
    path.is_file()
        && std::fs::File::open(path).is_ok_and(|mut f| f.read_exact(&mut magic).is_ok())
        && &magic == crate::npy::MAGIC
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crop_widens_to_the_aspect_within_the_frame() {
        let band = Crop {
            x: 0,
            y: 140,
            w: 592,
            h: 116,
        };
        let c = band.with_aspect(100.0 / 56.0, (640, 360));
        assert_eq!((c.w, c.h), (592, 332));
        assert!(c.y + c.h <= 360);
        let tall = Crop {
            x: 300,
            y: 0,
            w: 20,
            h: 100,
        };
        let c = tall.with_aspect(2.0, (640, 360));
        assert_eq!((c.w, c.h), (200, 100));
        assert_eq!(c.x, 210);
    }

    #[test]
    fn natural_order_sorts_numbers_by_value() {
        let mut v = vec!["f10.png", "f2.png", "f1.png", "f02b.png", "g.png"];
        v.sort_by(|a, b| natural_cmp(a, b));
        assert_eq!(v, ["f1.png", "f2.png", "f02b.png", "f10.png", "g.png"]);
    }
}
