//! Both routes' answer where the track's drain is in metres (`TrackRoute::drain_in_metres`: a
//! tank's empty time from its level's curve, and the heights a user read): the tank's k is the
//! track's where the track measures it more precisely than the latent, the latent's kept beside
//! it as its second opinion (`combine::combined`); where the latent is the more precise, its
//! answer stands. `gen`'s tanks filmed as videos, with three heights read from their
//! calibration: the track's k within 0.7 % on all three, the latent's 2–13 % low.

use super::combine::{combined, more_precise};
use crate::analysis::Run;
use crate::track::laws::TrackLaw;
use crate::track::TrackRoute;

/// `run`'s k made the track's where the track's drain gives one in metres and it is the more
/// precise; whether it changed.
pub fn combine_drain(run: &mut Run, route: &TrackRoute) -> bool {
    let Some(v) = route
        .guiding()
        .filter(|l| l.law == TrackLaw::Drain)
        .and_then(|l| l.si.iter().find(|v| v.name == "k"))
    else {
        return false;
    };
    let Some(i) = run.parameters.iter().position(|p| p.name == v.name) else {
        return false;
    };
    let p = &run.parameters[i];
    let Some(c) = combined(p, v, v.error).filter(|_| more_precise(p, v)) else {
        return false;
    };
    run.parameters[i] = c;
    true
}
