//! `ObservationMap`: how a shooting block's latent reads the observed state, latent = s·x + c per
//! coordinate, with s and c fixed, learned, or fitted to reference frames.

use tch::nn;
use tch::Tensor;

/// How the latent reads the observed state: latent = s·x + c per observed coordinate.
pub enum ObservationMap {
    /// s = 1, c = 0: the law itself does not care (a similarity-invariant system).
    Identity,
    /// log s and c learned with the other parameters.
    Learned { log_scale: Tensor, offset: Tensor },
    /// s and c fitted to reference frames of known value before every step (no gradient).
    Calibrated { scale: Tensor, offset: Tensor },
}

impl ObservationMap {
    /// The map of `d` latent coordinates under `path`, starting at scale `s` and offset `c`.
    pub fn new(path: &nn::Path, d: i64, s: f64, c: f64, calibrated: bool) -> ObservationMap {
        if calibrated {
            ObservationMap::Calibrated {
                scale: buffer(path, "scale", d, s),
                offset: buffer(path, "offset", d, c),
            }
        } else {
            ObservationMap::partly_learned(path, d, (s, true), (c, true))
        }
    }

    /// The map of `d` coordinates at scale `s` and offset `c`, each learned or held fixed (a
    /// part the law leaves free is held: learning it would only wander).
    pub fn partly_learned(
        path: &nn::Path,
        d: i64,
        (s, learn_scale): (f64, bool),
        (c, learn_offset): (f64, bool),
    ) -> ObservationMap {
        let part = |name: &str, v: f64, learn: bool| {
            if learn {
                path.var(name, &[d], nn::Init::Const(v))
            } else {
                buffer(path, name, d, v)
            }
        };
        ObservationMap::Learned {
            log_scale: part("log_scale", s.ln(), learn_scale),
            offset: part("offset", c, learn_offset),
        }
    }

    /// (s, c) as tensors [D], or `None` for the identity.
    pub(super) fn scale_offset(&self) -> Option<(Tensor, Tensor)> {
        match self {
            ObservationMap::Identity => None,
            ObservationMap::Learned { log_scale, offset } => {
                Some((log_scale.exp(), offset.shallow_clone()))
            }
            ObservationMap::Calibrated { scale, offset } => {
                Some((scale.shallow_clone(), offset.shallow_clone()))
            }
        }
    }
}

/// A variable `name` [d] under `path` that training does not move, at `v`.
fn buffer(path: &nn::Path, name: &str, d: i64, v: f64) -> Tensor {
    let mut t = path.zeros_no_train(name, &[d]);
    let _ = tch::no_grad(|| t.fill_(v));
    t
}
