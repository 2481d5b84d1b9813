//! `Scenario`: how the latent z becomes a picture (intensity, position or scale of a disc).

use crate::delfys::System;
use std::fmt;

/// The three synthetic scenes of the paper (appendix A.1). In each, |z| ≤ 1 keeps the object
/// inside the frame and the grey values inside [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Scenario {
    /// A fixed disc of radius 0.3·size whose grey level is 0.5 + 0.5·z.
    Intensity,
    /// A white disc of radius 0.1·size whose centre moves horizontally: x = size/2 + z·(size/2 − r − 1).
    Position,
    /// A white disc at the centre whose radius is size·(0.25 + 0.15·z).
    Scale,
    /// Delfys75: a bob on a string, θ'' = −(g/L)·sin θ − ζ·θ' (finite angles).
    Pendulum,
    /// Delfys75: a draining tank, h' = −k·√h.
    Torricelli,
    /// Delfys75: a block sliding down an incline, s'' = g·(sin α − μ·cos α).
    SlidingBlock,
    /// Delfys75: a dimming LED, I' = −γ·I.
    Led,
    /// Delfys75: a ball falling away from the camera, h'' = g, seen at radius f·r0/h.
    FreeFall,
}

/// A disc to draw: centre, radius (pixels) and grey level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    pub cx: f32,
    pub cy: f32,
    pub radius: f32,
    pub grey: f32,
}

impl Scenario {
    pub fn name(self) -> &'static str {
        match self {
            Scenario::Intensity => "intensity",
            Scenario::Position => "position",
            Scenario::Scale => "scale",
            Scenario::Pendulum => "pendulum",
            Scenario::Torricelli => "torricelli",
            Scenario::SlidingBlock => "sliding-block",
            Scenario::Led => "led",
            Scenario::FreeFall => "free-fall",
        }
    }

    /// The Delfys75 system of the scene, or `None` for the damped-oscillator scenes.
    pub fn system(self) -> Option<System> {
        match self {
            Scenario::Intensity | Scenario::Position | Scenario::Scale => None,
            Scenario::Pendulum => Some(System::Pendulum),
            Scenario::Torricelli => Some(System::Torricelli),
            Scenario::SlidingBlock => Some(System::SlidingBlock),
            Scenario::Led => Some(System::Led),
            Scenario::FreeFall => Some(System::FreeFall),
        }
    }

    /// The mapping from z to the picture, in words, for `meta.json`.
    pub fn mapping_text(self) -> &'static str {
        if let Some(system) = self.system() {
            return system.mapping_text();
        }
        match self {
            Scenario::Intensity => {
                "fixed anti-aliased disc of radius 0.3*size at the centre on black; grey level 0.5 + 0.5*z"
            }
            Scenario::Position => {
                "white anti-aliased disc of radius max(0.1*size, 1) on black; centre x = size/2 + z*(size/2 - radius - 1) pixels, y = size/2"
            }
            _ => "white anti-aliased disc at the centre on black; radius = size*(0.25 + 0.15*z) pixels",
        }
    }

    /// The disc that shows latent value `z` in a `size`×`size` frame (oscillator scenes).
    pub fn disc(self, z: f64, size: usize) -> Disc {
        let s = size as f32;
        let z = z as f32;
        match self {
            Scenario::Intensity => Disc {
                cx: s / 2.0,
                cy: s / 2.0,
                radius: 0.3 * s,
                grey: 0.5 + 0.5 * z,
            },
            Scenario::Position => {
                let r = position_radius(size);
                Disc {
                    cx: s / 2.0 + z * (s / 2.0 - r - 1.0),
                    cy: s / 2.0,
                    radius: r,
                    grey: 1.0,
                }
            }
            _ => Disc {
                cx: s / 2.0,
                cy: s / 2.0,
                radius: s * (0.25 + 0.15 * z),
                grey: 1.0,
            },
        }
    }
}

fn position_radius(size: usize) -> f32 {
    (0.1 * size as f32).max(1.0)
}

impl fmt::Display for Scenario {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn discs_stay_inside_the_frame_and_in_range_for_unit_latents() {
        for size in [8usize, 50, 128] {
            for sc in [Scenario::Intensity, Scenario::Position, Scenario::Scale] {
                for z in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                    let d = sc.disc(z, size);
                    let s = size as f32;
                    assert!(
                        d.cx - d.radius >= 0.0 && d.cx + d.radius <= s,
                        "{sc} {size} {z}"
                    );
                    assert!(d.cy - d.radius >= 0.0 && d.cy + d.radius <= s);
                    assert!(d.radius > 0.0 && (0.0..=1.0).contains(&d.grey));
                }
            }
        }
    }
}
