//! Which clips are independent draws: clips that share frames (a recording's, or windows cut
//! from one sequence into a data set) are grouped, and a recording's long windows are cut into
//! blocks of time; the covariance treats each group as one draw. Also the distinct frames of
//! such windows, for the fold test.

use crate::data::ClipData;
use crate::windows::Windows;
use tch::{Kind, Tensor};

/// Samples of a window per time block: residuals of nearby frames are correlated (the
/// encoder's errors are smooth in time), so blocks of this many samples, across all the
/// stride's phases, are the independent draws of a recording's covariance.
pub(super) fn time_blocks(w: &Windows) -> Vec<usize> {
    let len = w.frames[0].len();
    let block = ((len / 8).max(5) * w.stride).max(1);
    let keys: Vec<usize> = w.frames.iter().flatten().map(|&f| f / block).collect();
    renumber(&keys)
}

/// The group of each training clip: clips that share frames (a recording's, or windows cut
/// from one sequence into a data set) are not independent draws, so clips whose first frames
/// lie within a quarter of a clip's span of the sequence are one group (neighbouring groups
/// still share frames; a recording of one or two clips' length would otherwise give one
/// group and no error at all); clips that share none are each their own group.
pub(super) fn clip_groups(data: &ClipData) -> Vec<usize> {
    let n = data.n_train() as usize;
    let t = data.frames_per_clip as usize;
    // Each clip's sequence and the position of its first frame in it.
    let places: Vec<(usize, usize)> = match &data.recording {
        Some((summary, _)) => summary
            .clip_starts
            .iter()
            .take(n)
            .map(|&s| (0, s / summary.stride.max(1)))
            .collect(),
        None => {
            let offsets = window_offsets(&data.train);
            let mut places = Vec::with_capacity(n);
            for i in 0..n {
                let place = match (i.checked_sub(1), places.last()) {
                    (Some(prev), Some(&(seq, pos))) => match offsets[prev] {
                        Some(h) => (seq, pos + h),
                        None => (seq + 1, 0),
                    },
                    _ => (0, 0),
                };
                places.push(place);
            }
            places
        }
    };
    let block = (t / 4).max(1);
    let keys: Vec<(usize, usize)> = places.iter().map(|&(s, p)| (s, p / block)).collect();
    let mut distinct = keys.clone();
    distinct.sort_unstable();
    distinct.dedup();
    keys.iter()
        .map(|k| distinct.binary_search(k).unwrap_or(0))
        .collect()
}

/// For each clip but the last, the frame of it that the next clip starts with (the hop between
/// windows cut from one sequence), if any frame is identical to the next clip's first.
fn window_offsets(clips: &Tensor) -> Vec<Option<usize>> {
    let (n, t, _) = clips.size3().unwrap_or((0, 0, 0));
    if n < 2 {
        return Vec::new();
    }
    let mut out = Vec::with_capacity(n as usize - 1);
    for s in (0..n - 1).step_by(64) {
        let len = (n - 1 - s).min(64);
        let next = clips.narrow(0, s + 1, len).narrow(1, 0, 1);
        let same = tch::no_grad(|| {
            (clips.narrow(0, s, len) - next)
                .abs()
                .amax([2].as_slice(), false)
                .eq(0.0)
                .to_device(tch::Device::Cpu)
        });
        let rows = Vec::<Vec<bool>>::try_from(&same).unwrap_or_default();
        out.extend(
            rows.into_iter()
                .map(|r| r.iter().skip(1).position(|&b| b).map(|p| p + 1)),
        );
    }
    let _ = t;
    out
}

/// The distinct rows of `frames` [M, D] in their order (windows cut from one sequence repeat
/// its frames, and a repeated frame would be its own nearest neighbour), told apart by two
/// fixed projections.
pub(super) fn distinct_rows(frames: &Tensor) -> Tensor {
    let d = frames.size()[1];
    let keys = tch::no_grad(|| {
        let w = Tensor::arange(d, (Kind::Double, frames.device()));
        let p = Tensor::stack(&[(&w * 0.7548776662).sin(), (&w * 0.5698402910).cos()], 1);
        frames
            .to_kind(Kind::Double)
            .matmul(&p)
            .to_device(tch::Device::Cpu)
    });
    let keys = Vec::<Vec<f64>>::try_from(&keys).unwrap_or_default();
    let mut seen = std::collections::HashSet::new();
    let keep: Vec<i64> = keys
        .iter()
        .enumerate()
        .filter(|(_, k)| seen.insert((k[0].to_bits(), k[1].to_bits())))
        .map(|(i, _)| i as i64)
        .collect();
    if keep.len() == keys.len() {
        return frames.shallow_clone();
    }
    frames.index_select(0, &Tensor::from_slice(&keep).to_device(frames.device()))
}

/// Group numbers renumbered 0, 1, 2, … in order of first appearance.
pub(super) fn renumber(groups: &[usize]) -> Vec<usize> {
    let mut seen: Vec<usize> = Vec::new();
    groups
        .iter()
        .map(|g| match seen.iter().position(|s| s == g) {
            Some(i) => i,
            None => {
                seen.push(*g);
                seen.len() - 1
            }
        })
        .collect()
}
