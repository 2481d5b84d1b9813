//! A rectangle in the plane of the motion (`--plane X1,Y1:X2,Y2:X3,Y3:X4,Y4=WIDTHxHEIGHT`): its
//! four corners in the displayed frame (pixels, as an image viewer shows them, in order around
//! it: the first to the second along its width, the second to the third along its height) and
//! its size in metres. For a camera tilted to that plane, where one stick cannot carry the
//! picture's scale (it changes along the path), the homography from the picture to the plane
//! (Hartley and Zisserman's direct linear transform on four points, solved with nalgebra)
//! puts every position of the track in metres on the plane: the rectangle's first corner is
//! the origin, its width the plane's x and its height the plane's y.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};
use physvid_shared::cli::num;
use serde::{Deserialize, Serialize};

/// The plane of the motion, given by a rectangle in it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    /// The rectangle's corners in the displayed frame (pixels), in order around it.
    pub corners: [(f64, f64); 4],
    /// Its width (first corner to second) and height (second to third), metres.
    pub width: f64,
    pub height: f64,
}

/// A corner closer than this to the line through two others (pixels) leaves the rectangle's
/// picture without an area to map: a slip, or corners given out of order.
pub const LEAST_PIXELS: f64 = 5.0;

impl Plane {
    /// Parses `X1,Y1:X2,Y2:X3,Y3:X4,Y4=WIDTHxHEIGHT` (e.g. `80,30:160,30:143,134:71,134=4x6`).
    pub fn parse(text: &str) -> Result<Plane, String> {
        let bad = || {
            format!(
                "'{text}' is not X1,Y1:X2,Y2:X3,Y3:X4,Y4=WIDTHxHEIGHT: the four corners of a \
                 rectangle in the plane of the motion (pixels, in order around it) and its width \
                 and height in metres (e.g. 80,30:160,30:143,134:71,134=4x6)"
            )
        };
        let (points, size) = text.split_once('=').ok_or_else(bad)?;
        let parsed: Vec<(f64, f64)> = points
            .split(':')
            .map(|p| super::frame_point(text, p, "corner", bad))
            .collect::<Result<_, _>>()?;
        let corners: [(f64, f64); 4] = parsed.try_into().map_err(|_| bad())?;
        let (w, h) = size.split_once(['x', 'X']).ok_or_else(bad)?;
        let metres = |v: &str| -> Result<f64, String> {
            let m: f64 = v.trim().parse().map_err(|_| bad())?;
            if m.is_finite() && m > 0.0 && m <= super::MAX_REFERENCE {
                Ok(m)
            } else {
                Err(format!(
                    "'{text}': the side {} must be a length in metres, over 0 and at most {:e}",
                    num(m),
                    super::MAX_REFERENCE
                ))
            }
        };
        let plane = Plane {
            corners,
            width: metres(w)?,
            height: metres(h)?,
        };
        plane.check_shape(text)?;
        Ok(plane)
    }

    /// Refused where the corners do not go around a convex quadrilateral (each corner well
    /// off the line through its neighbours, all turning one way): what a rectangle's picture
    /// is, whatever the tilt.
    fn check_shape(&self, text: &str) -> Result<(), String> {
        let c = &self.corners;
        let mut turns = [0.0; 4];
        for i in 0..4 {
            let (a, b, p) = (c[(i + 3) % 4], c[(i + 1) % 4], c[i]);
            let cross = (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
            let base = (b.0 - a.0).hypot(b.1 - a.1).max(f64::MIN_POSITIVE);
            if (cross / base).abs() < LEAST_PIXELS {
                return Err(format!(
                    "'{text}': the corner {},{} lies on the line through its neighbours; give \
                     four corners of a rectangle, in order around it",
                    num(p.0),
                    num(p.1)
                ));
            }
            turns[i] = cross;
        }
        if !(turns.iter().all(|t| *t > 0.0) || turns.iter().all(|t| *t < 0.0)) {
            return Err(format!(
                "'{text}': the corners cross over; give them in order around the rectangle \
                 (e.g. top left, top right, bottom right, bottom left)"
            ));
        }
        Ok(())
    }

    /// The homography H (picture pixels to plane metres, up to scale): the 8×8 linear system
    /// of the four correspondences with H's last entry 1.
    fn homography(&self) -> Matrix3<f64> {
        let plane = [
            (0.0, 0.0),
            (self.width, 0.0),
            (self.width, self.height),
            (0.0, self.height),
        ];
        let mut a = SMatrix::<f64, 8, 8>::zeros();
        let mut b = SVector::<f64, 8>::zeros();
        for (i, (&(x, y), &(u, v))) in self.corners.iter().zip(&plane).enumerate() {
            let rows = [
                [x, y, 1.0, 0.0, 0.0, 0.0, -u * x, -u * y],
                [0.0, 0.0, 0.0, x, y, 1.0, -v * x, -v * y],
            ];
            for (k, row) in rows.iter().enumerate() {
                for (j, value) in row.iter().enumerate() {
                    a[(2 * i + k, j)] = *value;
                }
            }
            b[2 * i] = u;
            b[2 * i + 1] = v;
        }
        // A convex quadrilateral (`check_shape`) makes the system regular.
        let h = a.lu().solve(&b).unwrap_or_else(SVector::zeros);
        Matrix3::new(h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1.0)
    }

    /// The picture's point `(x, y)` (pixels) on the plane (metres from the first corner).
    pub fn to_plane(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let p = self.homography() * Vector3::new(x, y, 1.0);
        (p.x / p.z, p.y / p.z)
    }

    /// The plane's points `(x, y)` of the picture's points `xy` (faster than one by one).
    pub fn map(&self, xy: &[(f64, f64)]) -> Vec<(f64, f64)> {
        let h = self.homography();
        xy.iter()
            .map(|&(x, y)| {
                let p = h * Vector3::new(x, y, 1.0);
                (p.x / p.z, p.y / p.z)
            })
            .collect()
    }

    /// The picture's pixels a metre on the plane, over the rectangle: the square root of its
    /// picture's area over its own (the scale the track's pixel figures are read on).
    pub fn per_metre(&self) -> f64 {
        let c = &self.corners;
        let twice: f64 = (0..4)
            .map(|i| c[i].0 * c[(i + 1) % 4].1 - c[(i + 1) % 4].0 * c[i].1)
            .sum();
        (0.5 * twice.abs() / (self.width * self.height)).sqrt()
    }

    /// The plane's point `q` (metres) in the picture (pixels).
    pub fn to_picture(&self, q: (f64, f64)) -> (f64, f64) {
        let inverse = self
            .homography()
            .try_inverse()
            .unwrap_or_else(Matrix3::zeros);
        let v = inverse * Vector3::new(q.0, q.1, 1.0);
        (v.x / v.z, v.y / v.z)
    }

    /// A metre's step from the plane's point `p` (metres) along the plane's unit direction `d`
    /// as the picture draws it there (pixels, x and y): its length is the picture's scale
    /// there, its direction the motion's in the picture.
    pub fn drawn_at(&self, p: (f64, f64), d: (f64, f64)) -> (f64, f64) {
        let step = 1e-3 * self.width.min(self.height);
        let a = self.to_picture(p);
        let b = self.to_picture((p.0 + step * d.0, p.1 + step * d.1));
        ((b.0 - a.0) / step, (b.1 - a.1) / step)
    }

    /// The picture's pixels a metre at the plane's point `p` (metres) along the plane's unit
    /// direction `d` (`drawn_at`'s length: a tilted camera draws the far part smaller).
    pub fn pixels_per_metre_at(&self, p: (f64, f64), d: (f64, f64)) -> f64 {
        let (x, y) = self.drawn_at(p, d);
        x.hypot(y)
    }

    /// Refused where a corner lies outside a `width`×`height` frame, naming it.
    pub fn check_within(&self, width: usize, height: usize) -> Result<(), String> {
        super::within_frame("--plane", "corner", &self.corners, width, height)
    }

    /// As the flag is written.
    pub fn flag(&self) -> String {
        let corners: Vec<String> = self
            .corners
            .iter()
            .map(|p| format!("{},{}", num(p.0), num(p.1)))
            .collect();
        format!(
            "{}={}x{}",
            corners.join(":"),
            num(self.width),
            num(self.height)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 m × 6 m rectangle seen by a camera tilted about the picture's horizontal: its
    /// picture x = (20·X + 80)/(1 + 0.02·Y), y = (20·Y + 30)/(1 + 0.02·Y).
    pub(crate) fn tilted(p: (f64, f64)) -> (f64, f64) {
        let d = 1.0 + 0.02 * p.1;
        ((20.0 * p.0 + 80.0) / d, (20.0 * p.1 + 30.0) / d)
    }

    fn plane() -> Plane {
        let c = [(0.0, 0.0), (4.0, 0.0), (4.0, 6.0), (0.0, 6.0)].map(tilted);
        Plane {
            corners: c,
            width: 4.0,
            height: 6.0,
        }
    }

    #[test]
    fn a_tilted_rectangle_maps_back_to_the_plane() {
        let p = plane();
        for q in [(1.0, 2.0), (3.5, 5.5), (2.0, 9.0), (-1.0, 0.5)] {
            let back = p.to_plane(tilted(q));
            assert!(
                (back.0 - q.0).abs() < 1e-9 && (back.1 - q.1).abs() < 1e-9,
                "{q:?}: {back:?}"
            );
        }
        assert_eq!(
            p.map(&[tilted((1.0, 2.0))]),
            vec![p.to_plane(tilted((1.0, 2.0)))]
        );
        let there = p.to_picture((1.0, 2.0));
        let drawn = tilted((1.0, 2.0));
        assert!((there.0 - drawn.0).abs() < 1e-9 && (there.1 - drawn.1).abs() < 1e-9);
        // Down the plane at X = 2 m the picture steps 19.4 px down and 2.4 px in a metre at the
        // top, and (1 + 0.02·Y)² times less further down: 1.12² at 6 m.
        let top = p.pixels_per_metre_at((2.0, 0.0), (0.0, 1.0));
        let low = p.pixels_per_metre_at((2.0, 6.0), (0.0, 1.0));
        let drawn = 19.4f64.hypot(2.4);
        assert!((top - drawn).abs() < 0.05, "{top}");
        assert!((low - drawn / 1.12f64.powi(2)).abs() < 0.05, "{low}");
        assert!(p.per_metre() > low && p.per_metre() < top);
        assert_eq!(Plane::parse(&p.flag()).unwrap().flag(), p.flag());
    }

    #[test]
    fn what_is_no_rectangle_is_named() {
        for (text, says) in [
            ("0,0:10,0:10,10=1x1", "X1,Y1:X2,Y2:X3,Y3:X4,Y4"),
            ("0,0:10,0:10,10:0,10=1", "X1,Y1:X2,Y2:X3,Y3:X4,Y4"),
            ("0,0:10,0:10,10:0,10=1x0", "over 0"),
            ("0,0:10,0:10,10:-1,10=1x1", "in the frame"),
            ("0,0:10,0:20,0:0,10=1x1", "on the line"),
            ("0,0:10,10:10,0:0,10=1x1", "cross over"),
        ] {
            let e = Plane::parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
        }
        let p = Plane::parse("0,0:100,0:100,50:0,50=2x1").unwrap();
        assert!(p.check_within(100, 50).is_ok());
        assert!(p.check_within(99, 50).unwrap_err().contains("outside"));
    }
}
