//! The library API as a program calls it: a typed `Request` in, the fit with its verdict out,
//! nothing written; the same answer as the `estimate` binary on the same data (and on clips
//! held in memory as on their `.npy`), progress and cancellation passed in, and typed errors
//! for bad input.

mod util;

use estimator::data::Frames;
use estimator::{estimation, estimation_watched, EstimateError, Request, Watch};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use util::{estimate_of, gen_dataset, read_report, Estimate};

#[test]
fn the_api_answers_as_the_command_line_does_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("data"),
        "intensity",
        &["--samples", "120", "--size", "32", "--seed", "3"],
    );
    let cli_out = tmp.path().join("cli");
    Estimate::new(&data)
        .out(&cli_out)
        .args(["--threads", "2", "--epochs", "40"])
        .ok();
    let cli = read_report(&cli_out);

    let mut req = Request::new(&data);
    req.training.threads = 2;
    req.training.epochs = 40;
    req.quiet = true;
    req.out = tmp.path().join("never");
    let fit = estimation(&req).unwrap();
    assert!(!req.out.exists(), "a library call writes nothing");
    let run = &fit.report.run;
    assert_eq!(run.model, "damped-oscillator", "meta.json names the model");
    for name in ["gamma0", "gamma1"] {
        let api = run.parameters.iter().find(|p| p.name == name).unwrap();
        assert_eq!(api.estimate, estimate_of(&cli, name), "{name}");
    }
    assert_eq!(
        fit.report.verdict.grade.name(),
        cli["verdict"]["grade"].as_str().unwrap()
    );
    assert_eq!(run.epochs_run as u64, cli["epochs_run"].as_u64().unwrap());

    // Followed epoch by epoch, then stopped from the caller's side at the fifth.
    let (seen, stop) = (AtomicUsize::new(0), AtomicBool::new(false));
    let epoch = |rec: &estimator::train::EpochRecord, _: &[&str]| {
        if seen.fetch_add(1, Ordering::Relaxed) + 1 == 5 {
            stop.store(true, Ordering::Relaxed);
        }
        assert!(rec.epoch >= 1);
    };
    let watch = Watch {
        epoch: Some(&epoch),
        cancel: Some(&stop),
    };
    let e = estimation_watched(&req, watch).err().expect("cancelled");
    assert!(matches!(
        e.downcast_ref::<EstimateError>(),
        Some(EstimateError::Cancelled)
    ));
    let n = seen.load(Ordering::Relaxed);
    assert!(
        (5..run.epochs_run).contains(&n),
        "stopped at the next epoch's start ({n} seen, {} in a whole run)",
        run.epochs_run
    );
    assert!(!req.out.exists());

    // The same clips held in memory read as their bare .npy: the same answer.
    let npy = std::path::Path::new(&data).join("frames.npy");
    let array = physvid_shared::npy::read_npy(&npy).unwrap();
    let shape: [usize; 5] = array.shape.try_into().unwrap();
    let ask = |input: &str, frames: Option<Frames>| {
        let mut r = Request::new(input);
        r.load.model = Some(estimator::physics::ModelRef::by_name("damped-oscillator").unwrap());
        r.load.dt = Some(0.2);
        r.load.frames = frames.map(std::sync::Arc::new);
        (r.training.threads, r.training.epochs, r.quiet) = (2, 20, true);
        estimation(&r).unwrap().report.run.parameters
    };
    let from_file = ask(npy.to_str().unwrap(), None);
    let in_memory = ask("clips", Some(Frames::new(array.data, shape).unwrap()));
    for (a, b) in from_file.iter().zip(&in_memory) {
        assert_eq!((&a.name, a.estimate), (&b.name, b.estimate));
    }
}

#[test]
fn bad_input_is_a_typed_error_naming_it() {
    let tmp = tempfile::tempdir().unwrap();
    let missing = tmp.path().join("missing.npy");
    let mut req = Request::new(&missing);
    req.load.dt = Some(0.1);
    req.quiet = true;
    let e = estimation(&req).err().expect("no such file");
    let typed = e.downcast_ref::<EstimateError>().expect("an EstimateError");
    assert!(typed.to_string().contains("missing.npy"), "{typed}");
}
