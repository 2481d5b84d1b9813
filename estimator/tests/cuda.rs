//! CUDA path (only with `--features cuda-tests`, on a machine with an NVIDIA GPU): the same
//! training on the GPU recovers the parameters, and `--device auto` picks the GPU.
#![cfg(feature = "cuda-tests")]

mod util;

use clap::Parser;
use estimator::cli::DeviceChoice;
use estimator::config::RunConfig;
use estimator::data::{load_clips, probe};
use estimator::device::select_device;
use estimator::train::train;
use estimator::EstimateArgs;

#[test]
fn trains_on_the_gpu_and_recovers_the_parameters() {
    // select_device opens libtorch_cuda first: asking libtorch about CUDA before that would
    // disable it for the process.
    let (device, _) = select_device(DeviceChoice::Auto).unwrap();
    assert!(device.is_cuda(), "cuda-tests needs a CUDA GPU");
    let tmp = tempfile::tempdir().unwrap();
    let data_dir = util::gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "200", "--size", "32", "--seed", "5"],
    );
    let out = tmp.path().join("run");
    let args = EstimateArgs::try_parse_from([
        "estimate",
        &data_dir,
        "--single-start",
        "--device",
        "cuda",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ])
    .unwrap()
    .validate()
    .unwrap();
    let cfg = RunConfig::resolve(&args, probe(&args.load_request()).unwrap()).unwrap();
    let data = load_clips(&cfg.request, &cfg.plan, cfg.model, device).unwrap();
    assert!(data.train.device().is_cuda());
    let cfg = cfg.with_frames(&args, &data).unwrap();
    let outcome = train(&cfg, &data, device, &mut |_| {}).unwrap();
    let (g0, g1) = (outcome.parameters[0], outcome.parameters[1]);
    assert!((g0 / 4.0016 - 1.0).abs() < 0.01, "gamma0 {g0}");
    assert!((g1 / 0.08 - 1.0).abs() < 0.10, "gamma1 {g1}");
}

#[test]
fn the_binary_trains_on_the_gpu_by_default_and_agrees_with_the_cpu() {
    let tmp = tempfile::tempdir().unwrap();
    let data = util::gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "200", "--size", "32", "--seed", "6"],
    );
    let run = |name: &str, device: &[&str]| {
        let out = tmp.path().join(name);
        util::Estimate::new(&data)
            .args(["--single-start"])
            .args(device)
            .out(&out)
            .quiet()
            .ok();
        util::read_report(&out)
    };
    let gpu = run("gpu", &[]);
    let cpu = run("cpu", &["--device", "cpu"]);
    assert!(
        gpu["device"].as_str().unwrap().contains("Cuda"),
        "{}",
        gpu["device"]
    );
    assert!(
        cpu["device"].as_str().unwrap().contains("Cpu"),
        "{}",
        cpu["device"]
    );
    for name in ["gamma0", "gamma1"] {
        let (g, c) = (util::estimate_of(&gpu, name), util::estimate_of(&cpu, name));
        assert!((g / c - 1.0).abs() < 0.01, "{name}: GPU {g}, CPU {c}");
    }
}
