//! CUDA path (only with `--features cuda-tests`, on a machine with an NVIDIA GPU): the same
//! training on the GPU recovers the parameters, and `--device auto` picks the GPU.
#![cfg(feature = "cuda-tests")]

use estimator::config::{DeviceChoice, EstimateConfig};
use estimator::data::load_clips;
use estimator::encoder::EncoderKind;
use estimator::loss::LossKind;
use estimator::physics::Integrator;
use estimator::run::select_device;
use estimator::train::train;
use generator::{generate_to_disk, GenConfig, Scenario};

#[test]
fn trains_on_the_gpu_and_recovers_the_parameters() {
    assert!(tch::Cuda::is_available(), "cuda-tests needs a CUDA GPU");
    let device = select_device(DeviceChoice::Auto).unwrap();
    assert!(device.is_cuda());
    let tmp = tempfile::tempdir().unwrap();
    let data_dir = tmp.path().join("data");
    generate_to_disk(
        &GenConfig {
            scenario: Scenario::Intensity,
            out: data_dir.clone(),
            samples: 200,
            frames: 20,
            size: 32,
            dt: 0.2,
            omega: 2.0,
            zeta: 0.04,
            seed: 5,
            noise: 0.0,
            force: true,
            params: Default::default(),
        }
        .validate()
        .unwrap(),
    )
    .unwrap();
    let cfg = EstimateConfig {
        input: data_dir,
        dt: None,
        model: None,
        epochs: 300,
        patience: None,
        batch_size: 32,
        lr: 1e-3,
        lr_phys: 1e-2,
        init: vec![],
        reference: vec![],
        incline_deg: None,
        g: None,
        integrator: Integrator::Exact,
        single_start: true,
        loss: LossKind::MseKl,
        encoder: Some(EncoderKind::Small),
        seed: 0,
        ensemble: 1,
        recording: Default::default(),
        device: DeviceChoice::Cuda,
        threads: None,
        out: tmp.path().join("run"),
        quiet: true,
    };
    let data = load_clips(&cfg, device).unwrap();
    assert!(data.train.device().is_cuda());
    let init = cfg.initial_values(data.model).unwrap();
    let outcome = train(&cfg, &data, device, &init, &mut |_| {}).unwrap();
    let (g0, g1) = (outcome.parameters[0], outcome.parameters[1]);
    assert!((g0 / 4.0016 - 1.0).abs() < 0.01, "gamma0 {g0}");
    assert!((g1 / 0.08 - 1.0).abs() < 0.10, "gamma1 {g1}");
}
