//! Where the track's span lies in the picture: how far the object travels over it, and the
//! frame the latent route is trained on where the track guides it (the object's path, or a
//! brightness's region, widened).

use super::{LawSpan, TrackRoute};
use physvid_shared::video::Crop;

/// The frame the latent route is trained on where the track guides it (`frame_of`): the
/// object's path widened by this many of its sizes…
pub const FRAME_SIZES: f64 = 4.0;
/// …or by this share of the frame's short side, where that is more.
pub const FRAME_SHARE: f64 = 0.1;

impl TrackRoute {
    /// How far the object moves over the span `l`: its path's larger extent, as a share of the
    /// picture's larger side.
    pub fn travel(&self, l: &LawSpan) -> f64 {
        let t = &self.track;
        let size = |v: &[f64]| {
            let (lo, hi) = bounds(v, l);
            (hi - lo).max(0.0)
        };
        size(&t.x).max(size(&t.y)) / t.picture.0.max(t.picture.1).max(1) as f64
    }

    /// The rectangle of the displayed frame the object keeps to over the span `l`: its path's
    /// box widened on each side by [`FRAME_SIZES`] of the object's size, or by [`FRAME_SHARE`]
    /// of the frame's short side where that is more (the blob is the part of the object that
    /// differs in its sense: a card or a string beside it may not); a brightness's region
    /// (`Track::region`) widened by that share alone.
    pub fn frame_of(&self, l: &LawSpan) -> Crop {
        let t = &self.track;
        let (width, height) = t.picture;
        let share = FRAME_SHARE * width.min(height) as f64;
        // A brightness: the region whose light is read, widened by the frame's share alone
        // (the region is the whole of what changes).
        let ((x0, x1), (y0, y1), margin) = match t.region {
            Some((x0, y0, x1, y1)) => ((x0, x1), (y0, y1), share),
            None => (
                bounds(&t.x, l),
                bounds(&t.y, l),
                (FRAME_SIZES * t.size).max(share),
            ),
        };
        let side = |lo: f64, hi: f64, limit: usize| {
            let limit = limit.max(1) as f64;
            let a = (lo - margin).floor().clamp(0.0, limit - 1.0);
            let b = (hi + margin).ceil().clamp(a + 1.0, limit);
            (a as usize, (b - a) as usize)
        };
        let (x, w) = side(x0, x1, width);
        let (y, h) = side(y0, y1, height);
        Crop { x, y, w, h }
    }
}

/// The least and the greatest of `v` over the span `l`.
fn bounds(v: &[f64], l: &LawSpan) -> (f64, f64) {
    v[l.first..l.first + l.samples]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &a| {
            (lo.min(a), hi.max(a))
        })
}

#[cfg(test)]
mod tests {
    use crate::track::route::tests::route;

    #[test]
    fn the_frame_of_a_span_is_its_path_widened_and_kept_in_the_picture() {
        let (mut route, span) = route();
        // The margin: a tenth of the short side (30 px) over four sizes (24 px); the samples
        // outside the span (x 10) are left out.
        let c = route.frame_of(&span);
        assert_eq!((c.x, c.y, c.w, c.h), (70, 20, 100, 70));
        // A large object widens it by four of its sizes; the picture's edges bound it.
        route.track.size = 20.0;
        let c = route.frame_of(&span);
        assert_eq!((c.x, c.y, c.w, c.h), (20, 0, 200, 140));
    }
}
