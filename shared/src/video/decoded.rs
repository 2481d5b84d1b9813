//! `DecodedVideo`: a recording's kept frames, resized, on an even clock, and the clips cut from
//! them (by index: the frames are held once); and `SmallFrames`, a recording's frames as bytes
//! at one size, as the survey and the track read them.

use super::{VideoInfo, VideoOptions};

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
    /// Frames a second of the file's timeline, frame k at k / timeline_fps from the first kept:
    /// the container's rate, or the frames' own clock where it differs.
    pub timeline_fps: Option<f64>,
    /// What reading the frames on their own clock did (doubled, dropped or uneven frames), for
    /// a warning.
    pub clock_note: Option<String>,
    /// Seconds from the first frame read to frame 0: 0 unless frames at the start, off the
    /// even clock, were left out (`clock::Clock::head`); frame k lies at `first_s + k /
    /// timeline_fps` from the part's start.
    pub first_s: f64,
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

/// Clip starts over `count` frames for clips spanning `span` frames, and the hop between
/// them (`opts.hop`, or as small as keeps within `opts.max_clips`).
pub(super) fn cut(count: usize, span: usize, opts: &VideoOptions) -> (Vec<usize>, usize) {
    let possible = count.saturating_sub(span);
    let hop = opts
        .hop
        .unwrap_or_else(|| possible.div_ceil(opts.max_clips.max(1)).max(1));
    ((0..possible).step_by(hop).collect(), hop)
}

/// Frames of one size (grey, or chroma: `small_chroma`), row-major, one after another.
pub struct SmallFrames {
    pub pixels: Vec<u8>,
    pub size: (usize, usize),
}

impl SmallFrames {
    /// How many frames were decoded.
    pub fn len(&self) -> usize {
        self.pixels.len() / (self.size.0 * self.size.1).max(1)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Frame `i`.
    pub fn frame(&self, i: usize) -> &[u8] {
        let n = self.size.0 * self.size.1;
        &self.pixels[i * n..(i + 1) * n]
    }
}
