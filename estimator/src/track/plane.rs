//! The track on the plane of the motion (`--plane`, `calibration::Plane`): each position mapped
//! through the homography to metres on the plane and every law fitted again there, so that a
//! camera tilted to the motion (the far part of the path drawn smaller) reads as a camera
//! square to it; and the figures the guide and the verdict read off it: the scale the track's
//! pixel lengths are on, the picture's direction of a law on the plane, and how much one stick
//! would have been off along the path (`perspective`).

use super::{fit, LawSpan, TrackRoute};
use crate::calibration::Plane;

impl TrackRoute {
    /// The route read on `plane`: each position mapped to it, every law fitted again there in
    /// the plane's pixels (metres at `Plane::per_metre`, so that the track's noise and windows
    /// keep about their picture's sizes), and its pixel lengths also in metres.
    pub fn on_plane(mut self, plane: Plane) -> TrackRoute {
        let t = &mut self.track;
        let picture: Vec<(f64, f64)> = t.x.iter().copied().zip(t.y.iter().copied()).collect();
        t.on_plane = plane.map(&picture);
        let k = plane.per_metre();
        let xy: Vec<(f64, f64)> = t.on_plane.iter().map(|p| (p.0 * k, p.1 * k)).collect();
        let fitted = fit::fit(&t.t, &xy);
        (t.along, t.axis, t.noise) = (fitted.along, fitted.axis, fitted.noise);
        self.chosen = fitted.chosen;
        self.laws = fitted.laws;
        self.plane = Some(plane);
        self.in_metres(k)
    }

    /// The pixels a metre the track's lengths are read on: the plane's (`Plane::per_metre`)
    /// or the stick's; `None` without either.
    pub fn per_metre(&self) -> Option<f64> {
        self.plane
            .map(|p| p.per_metre())
            .or(self.stick.map(|s| s.per_metre()))
    }

    /// Sample `i`'s position as the laws were fitted on it: the picture's pixels, or the
    /// plane's (metres at `Plane::per_metre`).
    pub(crate) fn fitted_at(&self, i: usize) -> (f64, f64) {
        let t = &self.track;
        match (self.plane, t.on_plane.get(i)) {
            (Some(p), Some(q)) => (q.0 * p.per_metre(), q.1 * p.per_metre()),
            _ => (t.x[i], t.y[i]),
        }
    }

    /// The flag that gave the track its metres, as written (`--stick …`, `--plane …`).
    pub fn scale_flag(&self) -> Option<String> {
        match (self.plane, self.stick) {
            (Some(p), _) => Some(format!("--plane {}", p.flag())),
            (None, Some(s)) => Some(format!("--stick {}", s.flag())),
            (None, None) => None,
        }
    }

    /// The picture's unit direction (y down) of a law's direction `degrees` over the span
    /// `l`: itself in the picture, or, on a plane, the plane's direction drawn through the
    /// homography at the span's first position.
    pub fn picture_axis(&self, l: &LawSpan, degrees: f64) -> [f64; 2] {
        let (c, s) = (degrees.to_radians().cos(), degrees.to_radians().sin());
        let (Some(plane), Some(&q)) = (self.plane, self.track.on_plane.get(l.first)) else {
            return [c, s];
        };
        let (x, y) = plane.drawn_at(q, (c, s));
        let norm = x.hypot(y);
        if norm > 0.0 && norm.is_finite() {
            [x / norm, y / norm]
        } else {
            [c, s]
        }
    }

    /// On a plane, how much the picture's scale along the motion changes over the span `l`:
    /// the pixels a metre along its direction (the law's, else the track's axis) at its last
    /// position against at its first, less one, as a share (a stick's error along the path);
    /// `None` without a plane.
    pub fn perspective(&self, l: &LawSpan) -> Option<f64> {
        let plane = self.plane?;
        let t = &self.track;
        let (first, last) = (
            t.on_plane.get(l.first)?,
            t.on_plane.get(l.first + l.samples - 1)?,
        );
        let d = l
            .values
            .iter()
            .find(|v| v.name == "direction")
            .map_or(t.axis, |d| {
                (d.value.to_radians().cos(), d.value.to_radians().sin())
            });
        let (a, b) = (
            plane.pixels_per_metre_at(*first, d),
            plane.pixels_per_metre_at(*last, d),
        );
        Some((b / a - 1.0).abs()).filter(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::{laws::TrackLaw, Track};

    /// A drop from rest at 9.81 m/s² on a plane seen by a camera tilted about the picture's
    /// horizontal (x = (20·X + 80)/(1 + 0.02·Y), y = (20·Y + 30)/(1 + 0.02·Y), metres to
    /// pixels), 36 frames at 30 fps, as the track's picture positions.
    fn tilted_drop() -> (TrackRoute, Plane) {
        let tilted = |p: (f64, f64)| {
            let d = 1.0 + 0.02 * p.1;
            ((20.0 * p.0 + 80.0) / d, (20.0 * p.1 + 30.0) / d)
        };
        let t: Vec<f64> = (0..36).map(|i| i as f64 / 30.0).collect();
        let xy: Vec<(f64, f64)> = t.iter().map(|s| tilted((2.0, 4.905 * s * s))).collect();
        let (x, y): (Vec<f64>, Vec<f64>) = xy.iter().copied().unzip();
        let fitted = fit::fit(&t, &xy);
        let route = TrackRoute {
            track: Track {
                file_s: t.clone(),
                t,
                quality: vec![1.0; 36],
                x,
                y,
                along: fitted.along,
                axis: fitted.axis,
                noise: fitted.noise,
                size: 6.0,
                picture: (240, 200),
                frames: 36,
                threshold: 10.0,
                on_plane: Vec::new(),
                region: None,
                steadied: None,
                reading: crate::track::Reading::Centroids,
            },
            chosen: fitted.chosen,
            laws: fitted.laws,
            stick: None,
            plane: None,
            by_readings: None,
            shake: None,
        };
        let corners = [(0.0, 0.0), (4.0, 0.0), (4.0, 6.0), (0.0, 6.0)].map(tilted);
        let plane = Plane {
            corners,
            width: 4.0,
            height: 6.0,
        };
        (route, plane)
    }

    #[test]
    fn a_drop_seen_tilted_falls_at_g_on_its_plane() {
        let (route, plane) = tilted_drop();
        // In the picture the fall is no parabola: its scale shrinks by a fifth over the path.
        let acceleration = |r: &TrackRoute| {
            let l = r.accelerating()?;
            l.si.iter()
                .find(|v| v.name == "acceleration")
                .map(|v| v.value)
        };
        let r = route.on_plane(plane);
        assert_eq!(r.chosen, Some(TrackLaw::ConstantAcceleration));
        let g = acceleration(&r).expect("an acceleration in metres");
        assert!((g / 9.81 - 1.0).abs() < 1e-3, "{g}");
        let l = r.accelerating().unwrap();
        let change = r.perspective(l).unwrap();
        assert!(change > 0.15 && change < 0.25, "{change}");
        // The readings are the drop's own distances on the plane.
        let readings = r.readings(l, f64::NEG_INFINITY);
        let (t0, d0) = readings[0];
        for (t, d) in &readings {
            let want = 4.905 * (t * t - t0 * t0);
            assert!((d - d0 - want).abs() < 1e-3, "{t}: {d} for {want}");
        }
        // Straight down on the plane is straight down in the picture at x = 2 m's column.
        let axis = r.picture_axis(l, 90.0);
        assert!(axis[1] > 0.99, "{axis:?}");
        assert!(r.scale_flag().unwrap().starts_with("--plane "));
    }
}
