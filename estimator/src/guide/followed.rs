//! How much of the picture the track's law explains and folds, where the track guides the run
//! and its values are the answer (`combine`): the `motion` and `harmonic` checks' measure
//! (`evidence::fold`), taken of the coordinate the answer was read from, on the frames the
//! latent's was taken on. A latent that learned nothing of the picture (a 10-fps swing of
//! 100×56 pixels: −0.20) says nothing of a track whose law follows it (the same frames: 0.56),
//! and a track that followed a detail is caught here as a latent that did is.

use crate::analysis::Run;
use crate::evidence::fold::Fold;
use crate::track::TrackRoute;

/// The fold of the guiding track's law (its fitted position along its axis over its span,
/// `LawSpan::curve`: the motion the answer describes, without the reading's noise, which would
/// shuffle the frames' neighbours) in the principal components of the run's kept frames, each
/// frame matched to the track's sample within half a frame of it on the file's timeline (frames
/// without one left out); `None` where the track does not guide, the run has no value by its
/// rate's name (the answer is not the track's), the frames' components were not kept (a data
/// set, a latent of more than one number), or fewer than the fold's frames match.
pub fn followed(run: &Run, route: &TrackRoute) -> Option<Fold> {
    let span = route.guiding()?;
    let rate = span.rate()?.name;
    run.parameters.iter().find(|p| p.name == rate)?;
    let picture = run.evidence.picture.as_ref()?;
    let rec = run.recording.as_ref()?;
    let fps = [rec.timeline_fps, rec.fps]
        .into_iter()
        .find(|r| *r > 0.0 && r.is_finite())?;
    let track = &route.track;
    let last = span.first + span.curve.len();
    let first = span.first;
    if last > track.file_s.len() {
        return None;
    }
    let at = |row: usize| rec.start.unwrap_or(0.0) + (picture.first + row) as f64 / fps;
    let (rows, z) = matched(
        (0..picture.components.frames()).map(at),
        &track.file_s[first..last],
        &span.curve,
        0.5 / fps,
    );
    picture.components.rows(&rows).fold(&z)
}

/// The frames (their `times`, increasing) with a sample of the track (its times `file_s`,
/// increasing, and positions `along`) within `within` seconds: their rows and the samples'
/// positions.
fn matched(
    times: impl Iterator<Item = f64>,
    file_s: &[f64],
    along: &[f64],
    within: f64,
) -> (Vec<usize>, Vec<f64>) {
    let (mut rows, mut z) = (Vec::new(), Vec::new());
    let mut i = 0;
    for (row, at) in times.enumerate() {
        while i < file_s.len() && file_s[i] < at - within {
            i += 1;
        }
        if i < file_s.len() && (file_s[i] - at).abs() <= within {
            rows.push(row);
            z.push(along[i]);
        }
    }
    (rows, z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evidence::fold::Components;
    use tch::Tensor;

    #[test]
    fn each_frame_takes_the_track_s_sample_within_half_a_frame() {
        // Frames at 10 fps from 1.0 s; the track read at 5 fps from 1.2 s, a sample 0.01 s late.
        let times = (0..10).map(|k| 1.0 + k as f64 * 0.1);
        let file_s = [1.2, 1.41, 1.6, 1.8, 2.5];
        let along = [0.0, 1.0, 2.0, 3.0, 4.0];
        let (rows, z) = matched(times, &file_s, &along, 0.05);
        assert_eq!(rows, vec![2, 4, 6, 8]);
        assert_eq!(z, vec![0.0, 1.0, 2.0, 3.0]);
    }

    /// A dot swinging across a row of pixels: its position explains the picture, and a
    /// coordinate that ignores it (a slow drift) does not.
    #[test]
    fn the_track_s_position_explains_the_picture_a_drift_does_not() {
        let (n, w) = (120usize, 32usize);
        let x: Vec<f64> = (0..n)
            .map(|i| 15.5 + 10.0 * (i as f64 * 0.4).sin())
            .collect();
        let pix: Vec<f32> = x
            .iter()
            .flat_map(|&p| (0..w).map(move |c| (-(c as f64 - p).powi(2) / 4.0).exp() as f32))
            .collect();
        let frames = Tensor::from_slice(&pix).view([n as i64, w as i64]);
        let c = Components::of(&frames, true).unwrap();
        let every: Vec<usize> = (0..n).step_by(2).collect();
        let along: Vec<f64> = every.iter().map(|&i| x[i]).collect();
        let followed = c.rows(&every).fold(&along).unwrap();
        assert!(followed.explained_share > 0.9, "{followed:?}");
        let drift: Vec<f64> = every.iter().map(|&i| i as f64).collect();
        let detail = c.rows(&every).fold(&drift).unwrap();
        assert!(detail.explained_share < 0.5, "{detail:?}");
    }
}
