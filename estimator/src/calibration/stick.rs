//! A length in the picture (`--stick X1,Y1:X2,Y2=METRES`): two points of the displayed frame
//! (pixels, as an image viewer shows them) and the distance between them, as a lab sets its
//! video's scale by a metre stick, the marks on a ramp or bands behind a toss. It turns the
//! object's track into metres, and so the track's positions into reference readings.

use physvid_shared::cli::num;
use serde::{Deserialize, Serialize};

/// Two points of the displayed frame and the distance between them in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stick {
    pub from: (f64, f64),
    pub to: (f64, f64),
    pub metres: f64,
}

/// A stick shorter than this (pixels) sets no scale worth the name: a slip of the mouse.
pub const LEAST_PIXELS: f64 = 5.0;

impl Stick {
    /// Parses `X1,Y1:X2,Y2=METRES` (e.g. `284,45.5:284,446=1.0`).
    pub fn parse(text: &str) -> Result<Stick, String> {
        let bad = || {
            format!(
                "'{text}' is not X1,Y1:X2,Y2=METRES: two points of the frame in pixels and the \
                 distance between them (e.g. 284,45.5:284,446=1.0)"
            )
        };
        let (points, metres) = text.split_once('=').ok_or_else(bad)?;
        let (a, b) = points.split_once(':').ok_or_else(bad)?;
        let point = |p: &str| super::frame_point(text, p, "point", bad);
        let (from, to) = (point(a)?, point(b)?);
        let metres: f64 = metres.trim().parse().map_err(|_| bad())?;
        if !(metres.is_finite() && metres > 0.0 && metres <= super::MAX_REFERENCE) {
            return Err(format!(
                "'{text}': the length {} must be a distance in metres, over 0 and at most {:e}",
                num(metres),
                super::MAX_REFERENCE
            ));
        }
        let stick = Stick { from, to, metres };
        if stick.pixels() < LEAST_PIXELS {
            return Err(format!(
                "'{text}': its two points are {} px apart; give the ends of a length you can see \
                 (at least {LEAST_PIXELS} px)",
                num(stick.pixels())
            ));
        }
        Ok(stick)
    }

    /// Its length in pixels of the displayed frame.
    pub fn pixels(&self) -> f64 {
        (self.to.0 - self.from.0).hypot(self.to.1 - self.from.1)
    }

    /// Pixels of the displayed frame a metre.
    pub fn per_metre(&self) -> f64 {
        self.pixels() / self.metres
    }

    /// Refused where a point lies outside a `width`×`height` frame, naming it.
    pub fn check_within(&self, width: usize, height: usize) -> Result<(), String> {
        super::within_frame("--stick", "point", &[self.from, self.to], width, height)
    }

    /// As the flag is written.
    pub fn flag(&self) -> String {
        format!(
            "{},{}:{},{}={}",
            num(self.from.0),
            num(self.from.1),
            num(self.to.0),
            num(self.to.1),
            num(self.metres)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stick_reads_back_its_scale() {
        let s = Stick::parse("284,45.5:284,446=1.0").unwrap();
        assert!((s.per_metre() - 400.5).abs() < 1e-9);
        assert_eq!(Stick::parse(&s.flag()).unwrap(), s);
        assert!(s.check_within(640, 480).is_ok());
        assert!(s.check_within(320, 240).unwrap_err().contains("outside"));
    }

    #[test]
    fn what_is_no_stick_is_named() {
        for (text, says) in [
            ("284,45:284,446", "X1,Y1:X2,Y2=METRES"),
            ("284:446=1", "X1,Y1:X2,Y2=METRES"),
            ("a,1:2,3=1", "X1,Y1:X2,Y2=METRES"),
            ("1,1:100,1=0", "over 0"),
            ("1,1:100,1=inf", "over 0"),
            ("-1,1:100,1=1", "in the frame"),
            ("10,10:11,11=1", "px apart"),
        ] {
            let e = Stick::parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
        }
    }
}
