//! A recording in time: its frame rate (given, tagged, stamped or the container's), and the
//! stride between a clip's frames, Table 5's clip length by default, shortened where the part
//! kept is too short for it (with a warning saying so).

use super::RecordingRequest;
use crate::error::{input_error, EstimateError};
use crate::physics::ModelRef;
use physvid_shared::cli::approx;
use physvid_shared::video::VideoInfo;
use std::path::Path;

/// The stride: `--stride` when given; otherwise Table 5's clip time (`table_dt` at `fps`),
/// shortened so that a clip spans at most half of the frames kept within `trim` (when the
/// container's index counts them), with a warning naming the choice.
pub(super) fn stride(
    flag: Option<usize>,
    info: Option<&VideoInfo>,
    trim: (Option<f64>, Option<f64>),
    (frames_per_clip, table_dt, fps): (usize, f64, f64),
    model: ModelRef,
    warnings: &mut Vec<String>,
) -> usize {
    if let Some(s) = flag {
        return s;
    }
    let table = ((table_dt * fps).round() as usize).max(1);
    let Some(kept) = info.and_then(|i| i.frames_within(trim.0, trim.1)) else {
        return table;
    };
    let stride = fitting(table, frames_per_clip, kept);
    if stride < table {
        warnings.push(format!(
            "Table 5's clip of {} ({frames_per_clip} frames {} s apart: stride {table}) would \
             span more than half of the {kept} frames kept: stride {stride} ({} s between a \
             clip's frames) instead; --stride chooses",
            model.name(),
            approx(table_dt),
            approx(stride as f64 / fps)
        ));
    }
    stride
}

/// `table`, or the largest stride at which a clip of `frames_per_clip` frames spans at most
/// half of `kept` frames (at least 1).
fn fitting(table: usize, frames_per_clip: usize, kept: usize) -> usize {
    let gaps = frames_per_clip.saturating_sub(1).max(1);
    table.min((kept / 2 / gaps).max(1))
}

/// The frame rate of real time and where it came from: `--fps`; a slow-motion file's capture
/// tag where it disagrees with the container (with a warning); the frames' timestamps where the
/// container's rate disagrees with them or is missing; else the container's. Frames that are not
/// evenly spaced within the part kept are refused.
pub(super) fn frame_rate(
    input: &Path,
    info: Option<&VideoInfo>,
    flags: &RecordingRequest,
    warnings: &mut Vec<String>,
) -> Result<(f64, &'static str), EstimateError> {
    // The frames' own timestamps: the even clock they sit on within the part kept (doubled
    // and dropped frames placed on it, a GIF's rounded delays resampled onto it), or refused
    // with the numbers; its rate where the container gives none or another.
    let clock = match info.and_then(|i| i.clock(flags.start, flags.end)) {
        Some(Err(uneven)) => {
            return Err(input_error(format!(
                "{}: {}",
                input.display(),
                uneven.reason()
            )))
        }
        Some(Ok(c)) => Some(c),
        None => None,
    };
    let stamped = clock.map(|c| 1.0 / c.interval);
    let container = info.and_then(|i| i.container_fps);
    // A slow-motion capture: the file plays its frames slower than they were taken.
    let capture = info
        .and_then(|i| i.capture_fps.zip(i.container_fps))
        .filter(|(capture, container)| (capture / container - 1.0).abs() > 0.01);
    if let Some(f) = info.and_then(|i| i.fields) {
        warnings.push(format!(
            "interlaced ({}, as {} says{}): each frame's two fields are read as frames of \
             their own, at twice the frame rate (--fields frames reads the frames)",
            f.order.words(),
            match f.by {
                "picture" => "the picture",
                "container" => "the container's field-order tag",
                other => other,
            },
            f.voting.map_or(String::new(), |v| format!(
                ": on {} % of the frame pairs that move, the rows woven from one frame's field and \
                 the next frame's other comb clearly less than the other weave",
                approx(100.0 * v)
            )),
        ));
    }
    Ok(match (flags.fps, capture, container, stamped) {
        // --fps is the recording's frames per second; an interlaced one's fields come at twice.
        (Some(f), _, _, _) => (info.map_or(f, |i| i.read_rate(f)), "--fps"),
        (None, Some((capture, container)), _, _) => {
            warnings.push(format!(
                "the container says {} fps but the file's com.android.capture.fps tag says {} \
                 fps (a slow-motion capture): one frame is taken as 1/{} s of real time, and \
                 every rate with it; --fps overrides",
                approx(container),
                approx(capture),
                approx(capture)
            ));
            (capture, "capture tag")
        }
        // The container's rate is a nominal or average figure; the timestamps are the clock.
        (None, None, Some(c), Some(t)) if (c / t - 1.0).abs() > 0.001 => {
            if (c / t - 1.0).abs() > 0.01 {
                warnings.push(format!(
                    "the container says {} fps but the frames' timestamps are {} s apart ({} \
                     fps): the timestamps' rate is used",
                    approx(c),
                    approx(1.0 / t),
                    approx(t)
                ));
            }
            (t, "timestamps")
        }
        (None, None, Some(c), _) => (c, "container"),
        (None, None, None, Some(t)) => (t, "timestamps"),
        (None, None, None, None) => {
            return Err(input_error(format!(
                "{}: no frame rate known (an image folder, or a container without one): pass --fps",
                input.display()
            )))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_stride_stands_where_it_fits_and_shrinks_where_it_does_not() {
        // The jar trimmed to 13.75 s at 29.97 fps: Table 5's 1-s clip of 20 frames needs 571.
        assert_eq!(fitting(30, 20, 412), 10);
        assert!(19 * fitting(30, 20, 412) <= 412 / 2);
        // A long recording keeps the table's stride.
        assert_eq!(fitting(6, 20, 1320), 6);
        // Too few frames for any clip: stride 1 (the decoder then says what is missing).
        assert_eq!(fitting(30, 20, 10), 1);
        assert_eq!(fitting(30, 1, 100), 30);
    }

    #[test]
    fn a_given_stride_or_an_unknown_length_keeps_its_value_without_warning() {
        let model = ModelRef::by_name("torricelli").unwrap();
        let mut w = Vec::new();
        assert_eq!(
            stride(Some(7), None, (None, None), (20, 1.0, 30.0), model, &mut w),
            7
        );
        assert_eq!(
            stride(None, None, (None, None), (20, 1.0, 30.0), model, &mut w),
            30
        );
        assert!(w.is_empty());
    }
}
