//! Times that fit no even clock: the numbers and the frames a refusal names.

use super::MAX_MISSING;

/// Times that fit no even clock: the numbers for the refusal.
#[derive(Debug, Clone, PartialEq)]
pub struct Uneven {
    pub shortest: f64,
    pub longest: f64,
    pub median: f64,
    /// The best grid's worst deviation, in intervals.
    pub jitter: f64,
    /// A run of empty slots longer than [`MAX_MISSING`]: (the time it starts, slots missing).
    pub gap: Option<(f64, usize)>,
    /// The frames furthest off the best grid (their number from 1, their time), at most
    /// [`NAMED`] of them, the worst first.
    pub frames: Vec<(usize, f64)>,
}

/// How many of the frames off the grid a refusal names.
pub const NAMED: usize = 4;

impl Uneven {
    /// What is uneven, for a refusal, the times in seconds of the file's timeline.
    pub fn reason(&self) -> String {
        let ms = |s: f64| crate::cli::approx(s * 1e3);
        let what = match self.gap {
            Some((at, n)) => format!(
                "{n} frames are missing after {} s of the file's timeline (a pause or dropped \
                 frames; at most {MAX_MISSING} in a row are filled in)",
                crate::cli::approx(at)
            ),
            None => format!(
                "intervals from {} to {} ms (median {} ms) sit on no even clock (the best \
                 leaves a frame {:.0} % of an interval off, or too many frames missing){}",
                ms(self.shortest),
                ms(self.longest),
                ms(self.median),
                self.jitter * 100.0,
                self.named()
            ),
        };
        format!(
            "the frames are not evenly spaced in time: {what}; keep an even part with \
             --start/--end, or re-encode at a constant rate (ffmpeg -i IN -vf fps=RATE OUT.mp4)"
        )
    }
}

impl Uneven {
    /// The frames furthest off, for the refusal (empty where none is named).
    fn named(&self) -> String {
        if self.frames.is_empty() {
            return String::new();
        }
        let each: Vec<String> = self
            .frames
            .iter()
            .map(|(k, t)| format!("{k} ({} s)", crate::cli::approx(*t)))
            .collect();
        format!("; furthest off: frame {}", each.join(", "))
    }
}
