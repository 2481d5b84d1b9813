//! The shared recordings `reproduce real` estimates (`../shared/real-videos/`, their README):
//! each file with the readings its README offers for answers in SI (as options) and the values
//! known, with their bars and where they come from; and a few read as a lab would, by a stick
//! in the picture or the floor (`AS_A_LAB`).

use crate::options::Opt;

/// A value known for a recording: the model whose law is the system's, its parameter, the
/// value, and the bar (relative error).
pub struct Known {
    pub model: &'static str,
    pub parameter: &'static str,
    pub value: f64,
    pub bar: f64,
}

/// A shared recording: its file, the readings its README offers (as options), what is known.
pub struct Recording {
    pub file: &'static str,
    pub readings: &'static [Opt],
    pub known: &'static [Known],
    /// Where the known values come from.
    pub source: &'static str,
}

const fn known(model: &'static str, parameter: &'static str, value: f64, bar: f64) -> Known {
    Known {
        model,
        parameter,
        value,
        bar,
    }
}

/// The shared recordings (their README), the quick set first.
pub const RECORDINGS: [Recording; 14] = [
    Recording {
        file: "pendulum-redapple.mov",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 9.15, 0.02),
            known("pendulum", "g_over_l", 9.15, 0.02),
        ],
        source: "g/L from the period of the red bob tracked by hand, 2.077 ± 0.004 s",
    },
    Recording {
        file: "negative-tree.mov",
        readings: &[],
        known: &[],
        source: "a negative control: branches in the wind, no law",
    },
    Recording {
        file: "spring-k705.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 35.7, 0.02),
            known("pendulum", "g_over_l", 35.7, 0.02),
        ],
        source: "γ0 from the tracked period 1.051 s (the table's k/m gives 35.0)",
    },
    Recording {
        file: "spring-m515-hand.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 135.6, 0.02),
            known("pendulum", "g_over_l", 135.6, 0.02),
        ],
        source: "γ0 from the middle of the tracked periods, 0.537–0.542 s (134.4–136.9; the \
                 table's k/m gives 136.9), as for the other spring",
    },
    Recording {
        file: "incline-roll10.avi",
        readings: &[
            Opt::InclineDeg(10.3),
            Opt::Reference(&[(0.30, 0.076), (0.80, 0.360), (1.30, 0.855)]),
        ],
        known: &[known("sliding-block", "acceleration", 0.843, 0.03)],
        source: "a tracked on the ramp marks' scale, the readings' (about 6 % below the true a: the pipe runs farther from the camera than the marks)",
    },
    Recording {
        file: "freefall-ball.mp4",
        readings: &[Opt::Reference(&[(3.933, 0.0), (6.5, 1.975)])],
        known: &[known("free-fall", "g", 9.81, 0.03)],
        source: "g (the README: release near frame 118–124, the floor at 200–202)",
    },
    Recording {
        file: "torricelli-500ml.mp4",
        readings: &[Opt::Reference(&[(3.0, 0.0727), (12.0, 0.0373)])],
        known: &[known("torricelli", "k", 0.0170, 0.02)],
        source: "k from the two levels read (the README's discharge coefficient, about 0.55, \
                 gives 0.0147 and the bottom reached at 23–24 s gives 0.024: no better truth)",
    },
    Recording {
        file: "spring-k525.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 25.9, 0.02),
            known("pendulum", "g_over_l", 25.9, 0.02),
        ],
        source: "γ0 from the tracked period 1.2357 s (the table's k/m gives T = 1.231 s)",
    },
    Recording {
        file: "spring-m1715-hand.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 41.3, 0.02),
            known("pendulum", "g_over_l", 41.3, 0.02),
        ],
        source: "γ0 from the tracked period 0.9759 s; a hand holds the mass until about 2 s",
    },
    Recording {
        file: "spring-k506-fast.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 250.5, 0.02),
            known("pendulum", "g_over_l", 250.5, 0.02),
        ],
        source: "γ0 from the table's k/m (T 0.3965 s; tracked 0.3975–0.4005 s), about 12 frames \
                 a period",
    },
    Recording {
        file: "spring-phone-50g.mp4",
        readings: &[],
        known: &[
            known("damped-oscillator", "gamma0", 39.4, 0.02),
            known("pendulum", "g_over_l", 39.4, 0.02),
        ],
        source: "γ0 from 11 crossings (T 1.0011 s); a phone's variable frame rate, a hand until \
                 4.8 s",
    },
    Recording {
        file: "toss-tracker.mp4",
        readings: &[Opt::Reference(&[(0.37, 0.2008), (0.57, 0.0), (0.90, 0.5467)])],
        known: &[known("free-fall", "g", 9.80, 0.03)],
        source: "g; the readings are heights below the apex on the stick's scale (g 10.04 on \
                 it: the ball's plane is nearer the camera), not from rest",
    },
    Recording {
        file: "incline-roll17.avi",
        readings: &[
            Opt::InclineDeg(17.6),
            Opt::Reference(&[(0.2, 0.035), (0.6, 0.295), (1.1, 0.976)]),
        ],
        known: &[known("sliding-block", "acceleration", 1.585, 0.03)],
        source: "a of a pipe rolling without slipping (1.585 m/s², tracked alike on the marks' \
                 scale, 737–846 px/s² over fit windows: perspective)",
    },
    Recording {
        file: "pendulum-iris90.gif",
        readings: &[],
        known: &[known("pendulum", "g_over_l", 17.88, 0.02)],
        source: "g/L tracked by a nonlinear damped fit from 92° (10 fps GIF, held at first)",
    },
];

/// The same recordings read as a lab would, with what is in the picture (issue 64): a length
/// (`--stick`, the README's) and no `--reference`, or the floor at the ball's impact as its
/// second reading.
pub const AS_A_LAB: [Recording; 5] = [
    Recording {
        file: "freefall-ball.mp4",
        readings: &[Opt::Reference(&[(3.933, 0.0), (6.7, 2.26)])],
        known: &[known("free-fall", "g", 9.81, 0.03)],
        source: "g; the floor, 2.26 m below the ball at rest, reached at the impact",
    },
    Recording {
        file: "incline-roll10.avi",
        readings: &[Opt::Stick("64,294:582,407=1"), Opt::InclineDeg(10.3)],
        known: &[known("sliding-block", "acceleration", 0.843, 0.04)],
        source: "a; the ramp's marks 1 m apart as the stick (issue 64's bar: 4 %)",
    },
    Recording {
        file: "toss-tracker.mp4",
        readings: &[Opt::Stick("284,45.5:284,446=1")],
        known: &[known("free-fall", "g", 9.80, 0.04)],
        source: "g; the metre stick's bands as the stick, 400 px a metre (issue 64's bar: 4 %)",
    },
    Recording {
        file: "incline-roll17.avi",
        readings: &[Opt::Stick("139,225:586,404=1"), Opt::InclineDeg(17.6)],
        known: &[known("sliding-block", "acceleration", 1.585, 0.05)],
        source: "a; the ramp's marks as the stick (issue 64's bar: 5 %)",
    },
    Recording {
        file: "spring-k525.mp4",
        readings: &[Opt::Stick("915,395.5:915,749=0.2")],
        known: &[known("damped-oscillator", "gamma0", 25.9, 0.02)],
        source: "γ0 from the tracked period, and the track's amplitude in metres (the README's \
                 4.5 cm); the metre stick's 40 and 60 cm marks as the stick, read off the frame \
                 (17.68 px/cm; the README's 17.66)",
    },
];
