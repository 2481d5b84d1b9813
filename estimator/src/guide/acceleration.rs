//! Both routes' answer where the track accelerates at a constant rate in metres (by a stick, on
//! a plane, or by the `--reference` readings along its line): the fall's g or the slide's
//! acceleration is the track's where the track measures it more precisely than the latent (its
//! error, the larger of its fit's and its halves', the smaller), the latent's kept beside it as
//! its second opinion (`combine::combined`); the values the model derives from it (an
//! incline's friction) carried along (`combine::carry`). Where the latent is the more precise
//! (a short span the track holds, a slide seen in perspective) its answer stands, the track
//! compared with it by the routes check as before. Carts pulled from rest
//! (`scripts/carts_suite.py`): the track's is the answer on all six, within 0.7 %, its error
//! 2.6–100 times smaller than the latent's, which was 3–28 % low (four of six graded ok
//! before).

use super::combine::{carry, combined, more_precise};
use crate::analysis::Run;
use crate::track::TrackRoute;
use crate::verdict::routes::{si_acceleration, ACCELERATION_NAMES};

/// `run`'s acceleration in SI made the track's where the track's is the more precise (with the
/// value the model derives from it carried along); whether it changed. Only for a model whose
/// block has one value (the constant-acceleration models': the acceleration in the latent's
/// units, to which the SI value is proportional).
pub fn combine_acceleration(run: &mut Run, route: &TrackRoute) -> bool {
    let Some(v) = route.accelerating().and_then(si_acceleration) else {
        return false;
    };
    let names = run.config.model.parameter_names();
    let Some(k) =
        (run.parameters.iter()).position(|p| ACCELERATION_NAMES.contains(&p.name.as_str()))
    else {
        return false;
    };
    let p = &run.parameters[k];
    if names.len() != 1 || !more_precise(p, &v) || p.estimate == 0.0 {
        return false;
    }
    let Some(c) = combined(p, &v, v.error) else {
        return false;
    };
    let mut params = run.final_values.clone();
    params[0] *= c.estimate / p.estimate;
    let changed = vec![c.name.clone()];
    run.parameters[k] = c;
    let (model, cal) = (run.config.model, &run.calibration);
    carry(
        model,
        cal,
        [&run.final_values, &params],
        &mut run.parameters,
        &changed,
    );
    true
}
