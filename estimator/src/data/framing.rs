//! Framing: what part of a recording's frame the encoder sees. `--crop X,Y,W,H` as given,
//! `--crop full` the whole frame, and by default (`--crop auto`) the region where the picture
//! moves, from a quick survey at low resolution (`physvid_shared::video::survey`), at the
//! frame's shape (a tall region in a wide frame at its own), or the object's path where its
//! track guides the run (`guide`); and the figure that shows it above the clips.

use super::RecordingRequest;
use crate::error::{input_error, EstimateError};
use physvid_shared::video::{self, Crop, Survey, VideoInfo};
use serde::Serialize;
use std::path::Path;

/// `--crop`'s choice of what the encoder sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Framing {
    /// Where the picture moves (a survey of the recording).
    Auto,
    /// The whole frame.
    Full,
    /// The rectangle given.
    Crop(Crop),
    /// The object's path where its track guides the latent (`TrackRoute::frame_of`).
    Track(Crop),
}

/// An automatic crop covering more of the frame than this is not made (the whole frame is
/// kept): it would gain little resolution.
pub const AUTO_CROP_MAX_SHARE: f64 = 0.6;

/// The frame size fed to the encoder when `--size` is not given and the framed region is at
/// least as wide as it is tall (the paper's 100×56).
pub const DEFAULT_SIZE: (usize, usize) = (100, 56);

/// What the encoder sees of a recording.
pub struct Framed {
    /// The crop (`None`: the whole frame), and how it was chosen.
    pub crop: Option<Crop>,
    pub how: &'static str,
    /// The survey, when one was made.
    pub survey: Option<Survey>,
    /// The encoder's frame size: `--size`, else [`default_size`] of the shape of the given crop,
    /// of a tall region that moves in a wide frame, or of the whole frame.
    pub size: (usize, usize),
}

/// The encoder's frame size without `--size`, for a frame (or `--crop`) `aspect` (width /
/// height) wide:
/// [`DEFAULT_SIZE`] for a landscape or square one; for a portrait one as many pixels at its
/// shape (a phone held upright: 56×100; a ball's fall along a strip ten times taller than
/// wide: 24×237), so that the long side keeps its resolution.
pub fn default_size(aspect: f64) -> (usize, usize) {
    if !(aspect.is_finite() && aspect > 0.0) || aspect >= 1.0 {
        return DEFAULT_SIZE;
    }
    let pixels = (DEFAULT_SIZE.0 * DEFAULT_SIZE.1) as f64;
    let aspect = aspect.max(0.02);
    let w = (pixels * aspect).sqrt().round().max(8.0) as usize;
    let h = ((pixels / aspect).sqrt().round() as usize).min(4096);
    (w, h)
}

/// The shape whose encoder size frames the region that moves, `region`, in a frame of `frame`
/// (w, h): a tall region in a wide frame (a pendulum filmed landscape) keeps its own shape
/// rather than being widened into the rest of the picture (something else moving beside it);
/// otherwise the frame's (a small object's fast path, a fall's, moves each survey pixel too
/// briefly to be all in the region: a crop at the frame's shape reaches it).
fn auto_shape(region: Option<Crop>, frame: (usize, usize)) -> (usize, usize) {
    match region {
        Some(c) if c.h > c.w && frame.0 >= frame.1 => (c.w, c.h),
        _ => frame,
    }
}

/// The crop for `flags`, how it was chosen, the survey when one was made, and the encoder's
/// frame size; with `keep` (a model choice's candidate) the survey is shared with the other
/// candidates (`reuse::survey`).
pub fn frame(
    input: &Path,
    info: Option<&VideoInfo>,
    flags: &RecordingRequest,
    keep: bool,
) -> Result<Framed, EstimateError> {
    let size_for = |w: usize, h: usize| flags.size.unwrap_or(default_size(w as f64 / h as f64));
    let frame_size = info.map_or(flags.size.unwrap_or(DEFAULT_SIZE), |i| {
        size_for(i.width, i.height)
    });
    let whole = |how| Framed {
        crop: None,
        how,
        survey: None,
        size: frame_size,
    };
    Ok(match (flags.crop, info) {
        (Some(Framing::Crop(c)), _) => Framed {
            crop: Some(c),
            how: "--crop",
            survey: None,
            size: size_for(c.w, c.h),
        },
        (Some(Framing::Track(c)), _) => Framed {
            crop: Some(c),
            how: "the object's path, from its track",
            survey: None,
            size: size_for(c.w, c.h),
        },
        (Some(Framing::Full), _) => whole("whole frame (--crop full)"),
        (_, Some(i)) => {
            let s = super::reuse::survey(input, i, (flags.start, flags.end), false, keep)?;
            let frame = (i.width, i.height);
            let (w, h) = auto_shape(s.crop, frame);
            let size = size_for(w, h);
            // The region at the encoder's aspect ratio; not worth it over most of the frame.
            let crop = s
                .crop
                .map(|c| c.with_aspect(size.0 as f64 / size.1 as f64, frame))
                .filter(|c| c.area_share(frame) <= AUTO_CROP_MAX_SHARE);
            let how = if crop.is_some() {
                "where the picture moves (--crop auto)"
            } else {
                "whole frame: the motion fills most of it (--crop auto)"
            };
            Framed {
                crop,
                how,
                survey: Some(s),
                size,
            }
        }
        (_, None) => whole("whole frame (an image folder)"),
    })
}

/// The most memory a recording's frames and clips may take (bytes).
pub const MAX_BYTES: u64 = 8 << 30;

/// Refuses, before any decoding, a recording whose kept frames at `size` and the clips gathered
/// from them would not fit in memory (a 4096×4096 size on a minute of video asks for 87 GB).
pub fn check_memory(
    input: &Path,
    info: Option<&VideoInfo>,
    flags: &RecordingRequest,
    size: (usize, usize),
    frames_per_clip: usize,
    max_clips: usize,
) -> Result<(), EstimateError> {
    let frames_kept = info.map_or_else(
        || video::image_files(input).map_or(0, |f| f.len()),
        |i| {
            let t0 = i.frame_times.first().copied().unwrap_or(0.0);
            let (lo, hi) = (
                t0 + flags.start.unwrap_or(0.0),
                flags.end.map_or(f64::INFINITY, |e| t0 + e),
            );
            i.frame_times
                .iter()
                .filter(|t| **t >= lo && **t < hi)
                .count()
        },
    );
    let per_frame = (size.0 * size.1 * 4) as u64;
    let clips_max = (max_clips * frames_per_clip) as u64;
    let bytes = per_frame
        * (frames_kept as u64 + clips_max.min(frames_kept as u64 * frames_per_clip as u64));
    if bytes > MAX_BYTES {
        return Err(input_error(format!(
            "{}: {frames_kept} frames of {}×{} (and the clips cut from them) need {:.1} GB, more \
             than the {} GB taken; lower --size, or trim with --start/--end",
            input.display(),
            size.0,
            size.1,
            bytes as f64 / 1e9,
            MAX_BYTES >> 30
        )));
    }
    Ok(())
}

/// The survey's motion map (grey) with the crop drawn in red, scaled to the width of `sheet`,
/// above it.
pub fn drawn_over(
    survey: &Survey,
    crop: Option<Crop>,
    full_width: usize,
    sheet: &image::DynamicImage,
) -> image::DynamicImage {
    use image::{Rgb, RgbImage};
    let (w, h) = survey.map_size;
    let scale = (sheet.width() as usize / w.max(1)).clamp(1, 4);
    let (mw, mh) = (w * scale, h * scale);
    let width = (sheet.width() as usize).max(mw);
    let mut out = RgbImage::new(width as u32, (mh + 4) as u32 + sheet.height());
    for y in 0..mh {
        for x in 0..mw {
            let v = (survey.map[(y / scale) * w + x / scale].clamp(0.0, 1.0) * 255.0) as u8;
            out.put_pixel(x as u32, y as u32, Rgb([v, v, v]));
        }
    }
    if let Some(c) = crop {
        let f = mw as f64 / full_width.max(1) as f64;
        let (x0, y0) = ((c.x as f64 * f) as u32, (c.y as f64 * f) as u32);
        let x1 = (((c.x + c.w) as f64 * f) as u32).min(mw as u32 - 1);
        let y1 = (((c.y + c.h) as f64 * f) as u32).min(mh as u32 - 1);
        for x in x0..=x1 {
            out.put_pixel(x, y0, Rgb([230, 40, 30]));
            out.put_pixel(x, y1, Rgb([230, 40, 30]));
        }
        for y in y0..=y1 {
            out.put_pixel(x0, y, Rgb([230, 40, 30]));
            out.put_pixel(x1, y, Rgb([230, 40, 30]));
        }
    }
    let sheet = sheet.to_rgb8();
    for (x, y, p) in sheet.enumerate_pixels() {
        out.put_pixel(x, y + mh as u32 + 4, *p);
    }
    image::DynamicImage::ImageRgb8(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tall_region_keeps_its_shape_in_a_wide_frame_only() {
        let tall = Crop {
            x: 34,
            y: 0,
            w: 134,
            h: 166,
        };
        assert_eq!(auto_shape(Some(tall), (320, 180)), (134, 166));
        let size = default_size(134.0 / 166.0);
        assert!(size.1 > size.0, "{size:?}");
        // In a tall frame (the ball's strip) and for a wide region, the frame's shape.
        assert_eq!(auto_shape(Some(tall), (172, 1716)), (172, 1716));
        let wide = Crop {
            w: 166,
            h: 134,
            ..tall
        };
        assert_eq!(auto_shape(Some(wide), (320, 180)), (320, 180));
        assert_eq!(auto_shape(None, (320, 180)), (320, 180));
    }
}
