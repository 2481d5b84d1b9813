//! The pictures of the whole recording read in the look's pass beside the frames it looks at
//! (`picture::look`), for the later reads of the same file (`kept`): the whole at the track's
//! size, at the survey's, at its own, and in colour at the track's for a short one.

use super::super::kept::{Wholes, LARGE_AT_MOST};
use super::super::small::{small_filter, small_size, KEPT_AT_MOST, SURVEY_SIDE, TRACK_SIDE};
use super::super::tools::EVERY_FRAME;
use super::super::SmallFrames;
use std::path::PathBuf;
use std::process::Command;

/// A picture read beside the look: its label, its filter, its size, its pixel format (and its
/// bytes a pixel) and its file.
type Picture = (
    &'static str,
    String,
    (usize, usize),
    (&'static str, usize),
    PathBuf,
);
const GREY: (&str, usize) = ("gray", 1);
const COLOUR: (&str, usize) = ("yuv444p", 3);

/// The most bytes of colour at the track's size read beside the look (three a pixel): a short
/// recording's, whose decode costs less than its start. Measured: the 90° GIF's 7 MB, its run
/// 0.1 s faster (its colour's own decode gone); the tree's 57 MB, its run 0.15 s slower. Bounds
/// time only; no decision reads it (the chroma is the same byte for byte).
const COLOUR_AT_MOST: usize = 16 << 20;

/// What is read beside the look of a recording, and where.
pub(super) struct Beside {
    pictures: Vec<Picture>,
    /// The recording's own size, whether it is kept apart from the track's, and whether
    /// `frames` of it are within [`LARGE_AT_MOST`].
    large: ((usize, usize), bool, bool),
    /// The files' folder (removed when this is dropped), and ffmpeg's complaints there.
    _scratch: Option<tempfile::TempDir>,
    pub log: Option<PathBuf>,
}

impl Beside {
    /// What to read beside the look of a recording of stored `size` (w, h) and `frames`
    /// frames: the whole at the track's size where its size is known and within
    /// [`KEPT_AT_MOST`]; at the survey's and its own size too where they differ (its own within
    /// [`LARGE_AT_MOST`]); in colour at the track's within [`COLOUR_AT_MOST`]. Nothing where the
    /// frames could not be written to a temporary file (the look alone is its purpose).
    pub fn plan(size: (usize, usize), frames: Option<usize>) -> Beside {
        let at_most = |size: (usize, usize), most: usize| {
            frames.is_some_and(|n| n.saturating_mul(size.0 * size.1) <= most)
        };
        let whole = small_size(size, TRACK_SIDE);
        let survey = small_size(size, SURVEY_SIDE);
        let fits = at_most(whole, KEPT_AT_MOST);
        let large_within = at_most(size, LARGE_AT_MOST);
        let large_apart = fits && size != whole && large_within;
        let colour = fits && at_most(whole, COLOUR_AT_MOST / COLOUR.1);
        let scratch = tempfile::tempdir().ok().filter(|_| fits);
        let file = |name: &str| scratch.as_ref().map(|d| d.path().join(name));
        let pictures = [
            ("whole", small_filter(whole), whole, GREY, true),
            (
                "survey",
                small_filter(survey),
                survey,
                GREY,
                survey != whole,
            ),
            ("large", "null".to_string(), size, GREY, large_apart),
            ("colour", small_filter(whole), whole, COLOUR, colour),
        ]
        .into_iter()
        .filter_map(|(label, filter, size, format, wanted)| {
            let out = file(&format!("{label}.raw")).filter(|_| wanted)?;
            Some((label, filter, size, format, out))
        })
        .collect();
        Beside {
            pictures,
            large: (size, large_apart, large_within),
            log: file("log"),
            _scratch: scratch,
        }
    }

    /// ffmpeg's `cmd` (its input given) told to read the pictures beside, each to its file
    /// (every frame, as `small_frames` and `small_chroma` read it; the larger at the file's own
    /// size, as `decode` converts it, no scaling), and the frames `looked` at (a filter) to
    /// be mapped next: one decode, split.
    pub fn args(&self, cmd: &mut Command, looked: &str) {
        if self.pictures.is_empty() {
            cmd.args(["-map", "0:v:0", "-vf", looked]);
            return;
        }
        let n = self.pictures.len();
        let mut graph = format!("[0:v:0]split={}", n + 1);
        (0..=n).for_each(|i| graph.push_str(&format!("[s{i}]")));
        for (i, (label, filter, ..)) in self.pictures.iter().enumerate() {
            graph.push_str(&format!(";[s{i}]{filter}[{label}]"));
        }
        graph.push_str(&format!(";[s{n}]{looked}[looked]"));
        cmd.args(["-filter_complex", &graph]);
        for (label, _, _, (format, _), out) in &self.pictures {
            cmd.args(["-map", &format!("[{label}]")])
                .args(&EVERY_FRAME[2..])
                .args(["-f", "rawvideo", "-pix_fmt", format, "-y"])
                .arg(out);
        }
        cmd.args(["-map", "[looked]"]);
    }

    /// The pictures read, where the pass was `done`: none at its own size where ffmpeg
    /// complained of the file (`clean` false: it is decoded again, and its damage reported).
    pub fn read(self, done: bool, clean: bool) -> Wholes {
        let mut read: Vec<Option<SmallFrames>> = ["whole", "survey", "large", "colour"]
            .iter()
            .map(|name| {
                let (_, _, size, (_, bytes), file) = self.pictures.iter().find(|b| b.0 == *name)?;
                let pixels = std::fs::read(file).ok().filter(|_| done)?;
                let whole_frames =
                    !pixels.is_empty() && pixels.len() % (size.0 * size.1 * bytes) == 0;
                whole_frames.then_some(SmallFrames {
                    pixels,
                    size: *size,
                })
            })
            .collect();
        let whole = read[0].take();
        // A picture of the same size as the whole's is its frames.
        let same = |size: (usize, usize)| {
            let f = whole.as_ref().filter(|f| f.size == size)?;
            Some(SmallFrames {
                pixels: f.pixels.clone(),
                size,
            })
        };
        let (size, apart, within) = self.large;
        let large = match (clean, apart) {
            (false, _) => None,
            (true, true) => read[2].take(),
            (true, false) => same(size).filter(|_| within),
        };
        Wholes {
            survey: read[1]
                .take()
                .or_else(|| same(small_size(size, SURVEY_SIDE))),
            large,
            colour: read[3].take().map(|f| f.pixels),
            whole,
        }
    }
}
