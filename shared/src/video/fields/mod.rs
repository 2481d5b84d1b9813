//! Interlaced recordings: a camera that writes two fields a frame (the even rows, then the odd
//! rows a half interval later) shows a moving object twice, combed, in every frame; read as
//! frames it is measured at half its rate between two places. Such a recording is read as its
//! fields, each made a whole frame by ffmpeg's `yadif` (the field's rows kept, the others
//! interpolated), at twice the frame rate, in the order they were taken.
//!
//! Found from the picture (`picture.rs`): where two frames differ, the rows woven from one frame's
//! field and the next frame's other field comb less than the other weave when the fields were
//! taken half an interval apart in that order, and alike when both fields of a frame were taken
//! at once. Where nothing moves enough to tell, the container's field-order tag says. Measured
//! on frame pairs that move: recordings interlaced here with ffmpeg's `tinterlace` (a square and
//! a disc swinging, a disc falling, the shared pendulum; both orders) vote 70–99 % for their
//! order and none for the other (a disc swinging 3 pixels: 35 %); the shared recordings and the
//! same drawings progressive 0–6 %, split evenly.

mod beside;
mod picture;

use super::VideoError;
use picture::Look;
use serde::Serialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// Which field was taken first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FieldOrder {
    TopFirst,
    BottomFirst,
}

impl FieldOrder {
    /// In words, for messages.
    pub fn words(self) -> &'static str {
        match self {
            FieldOrder::TopFirst => "top field first",
            FieldOrder::BottomFirst => "bottom field first",
        }
    }
}

/// How a recording's fields are read (`--fields`): found from the picture or the tag
/// (`auto`), never split (`frames`), or split in the order given.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "kebab-case")]
pub enum FieldsChoice {
    #[default]
    Auto,
    Frames,
    TopFirst,
    BottomFirst,
}

/// An interlaced recording's fields: their order and what said so.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fields {
    pub order: FieldOrder,
    /// "picture" (its rows comb where it moves), "container" (its field-order tag, where
    /// nothing moves enough to tell) or "--fields".
    pub by: &'static str,
    /// The share of the frame pairs that move which voted for this order (the picture's; see
    /// the module's measurements).
    pub voting: Option<f64>,
}

impl Fields {
    /// ffmpeg's filter that makes each field a frame, in the order they were taken.
    pub fn filter(&self) -> String {
        let parity = match self.order {
            FieldOrder::TopFirst => "tff",
            FieldOrder::BottomFirst => "bff",
        };
        format!("yadif=mode=send_field:parity={parity}:deint=all")
    }
}

/// The fields `choice` gives without looking (`frames`: none; an order: that order), or
/// `None` where the picture and the tag are to say (`auto`).
pub fn chosen(choice: FieldsChoice) -> Option<Option<Fields>> {
    let order = match choice {
        FieldsChoice::Auto => return None,
        FieldsChoice::Frames => return Some(None),
        FieldsChoice::TopFirst => FieldOrder::TopFirst,
        FieldsChoice::BottomFirst => FieldOrder::BottomFirst,
    };
    Some(Some(Fields {
        order,
        by: "--fields",
        voting: None,
    }))
}

/// The order a container's `field_order` tag says (ffprobe's tt, bb, tb, bt: the first
/// letter the field coded first, the second the one shown first).
pub fn from_tag(tag: &str) -> Option<FieldOrder> {
    match tag {
        "tt" | "bt" => Some(FieldOrder::TopFirst),
        "bb" | "tb" => Some(FieldOrder::BottomFirst),
        _ => None,
    }
}

/// The fields of the recording at `path` (stored `size` (w, h), `frames` in all, `tag` its
/// container's field order), or `None` when it is progressive. Decodes the recording once
/// more (`picture`: its first frames looked at, the whole at the track's size kept for the
/// track where it is progressive); remembered per file for the process (probed again by
/// model choice and the run).
pub fn find(
    path: &Path,
    size: (usize, usize),
    frames: Option<usize>,
    tag: Option<FieldOrder>,
) -> Result<Option<Fields>, VideoError> {
    static SEEN: OnceLock<Mutex<HashMap<PathBuf, Option<Fields>>>> = OnceLock::new();
    let seen = SEEN.get_or_init(Default::default);
    if let Some(f) = seen.lock().ok().and_then(|s| s.get(path).copied()) {
        return Ok(f);
    }
    let (look, wholes) = picture::look(path, size, frames)?;
    let fields = match (look, tag) {
        (Look::Interlaced(order, share), _) => Some(Fields {
            order,
            by: "picture",
            voting: Some(share),
        }),
        (Look::Unknown, Some(order)) => Some(Fields {
            order,
            by: "container",
            voting: None,
        }),
        _ => None,
    };
    if fields.is_none() {
        super::kept::keep(path, wholes);
    }
    if let Ok(mut s) = seen.lock() {
        s.insert(path.to_path_buf(), fields);
    }
    Ok(fields)
}

/// The fields' times: each frame's time, and half its interval after it (the last frame's
/// interval the one before it).
pub fn times(frames: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(2 * frames.len());
    for (i, &t) in frames.iter().enumerate() {
        let next = frames.get(i + 1).copied();
        let step = match (next, i.checked_sub(1).map(|j| frames[j])) {
            (Some(n), _) => n - t,
            (None, Some(p)) => t - p,
            (None, None) => 0.0,
        };
        out.push(t);
        out.push(t + step / 2.0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_fall_half_way_between_frames_and_tags_read_as_ffmpeg_writes_them() {
        let t = times(&[0.0, 0.1, 0.3]);
        let want = [0.0, 0.05, 0.1, 0.2, 0.3, 0.4];
        assert!(t.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12) && t.len() == 6);
        assert_eq!(from_tag("tt"), Some(FieldOrder::TopFirst));
        assert_eq!(from_tag("bb"), Some(FieldOrder::BottomFirst));
        assert_eq!(from_tag("progressive"), None);
        assert_eq!(from_tag("unknown"), None);
    }
}
