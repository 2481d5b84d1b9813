//! Tests of `smooth.rs`: the map takes a compressed read out of the damping (the pendulum's
//! law, as the shooting blocks integrate it).
use super::super::ObservationMap;
use super::*;
use crate::physics::pendulum::PendulumSystem;
use crate::physics::{Bounds, ParamSpec, Settles};
use tch::nn;

#[test]
fn the_smooth_map_takes_a_compressed_read_out_of_the_damping() {
    let (w2, zeta, dt, frames) = (4.0, 0.08, 0.2, 20);
    let span = Span {
        t0: 0.0,
        dt,
        frames,
        substeps: 8,
    };
    // Clips of the law read through a map that flattens the extremes.
    let z: Vec<f32> = (0..60)
        .flat_map(|i| {
            let amp = 0.5 + 0.5 * (i as f64 * 0.618).fract();
            let x0 = [amp * (i as f64).cos(), 2.0 * amp * (i as f64).sin()];
            integrate(&PendulumSystem, &x0, &[w2, zeta], span, &[0], false).y
        })
        .map(|x| (0.1 + x - 0.08 * x * x * x) as f32)
        .collect();
    let z = Tensor::from_slice(&z).view([60, frames as i64, 1]);
    let vs = nn::VarStore::new(tch::Device::Cpu);
    let spec = |name, start| ParamSpec {
        name,
        start,
        bounds: Bounds::new(Some(0.0), None),
        settles: Settles::Relative,
    };
    let block = ShootingBlock::new(
        &vs.root(),
        Box::new(PendulumSystem),
        &[spec("g_over_l", w2), spec("zeta", zeta)],
        &[w2, zeta],
        ObservationMap::Identity,
        vec![0],
        dt,
        8,
    );
    let ids: Vec<usize> = (0..60).collect();
    let clips = Clips {
        start: None,
        ids: Some(&ids),
    };
    block.refine(&z, clips, 20);
    let affine = host(&block.physical());
    assert!((affine[1] / zeta - 1.0).abs() > 0.01, "{affine:?}");
    assert!(block.refine_smooth(&z, clips, 40));
    let smooth = host(&block.physical());
    assert!(
        (smooth[0] / w2 - 1.0).abs() < 1e-4 && (smooth[1] / zeta - 1.0).abs() < 1e-3,
        "{smooth:?}"
    );
}
