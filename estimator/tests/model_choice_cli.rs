//! The model chosen by the evidence end to end: `--model auto` on a data set (meta.json's model
//! set aside), no `--model` on a bare `.npy`, the ranking in report.json, report.html and the
//! table, `--candidate`'s refusals, and the library's choice handing back the chosen one's clips.

mod util;

use util::{gen_dataset, oscillator_video, read_report, stderr, Estimate};

/// report.json's `model_choice`: the chosen model and the candidates' names, ranked.
fn choice(report: &serde_json::Value) -> (String, Vec<String>) {
    let c = &report["model_choice"];
    let names = c["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["model"].as_str().unwrap().to_string())
        .collect();
    (c["chosen"].as_str().unwrap().to_string(), names)
}

#[test]
fn a_dimming_led_is_told_from_the_other_laws() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("led"),
        "led",
        &["--samples", "60", "--size", "24", "--seed", "5"],
    );
    let out = tmp.path().join("auto");
    let o = Estimate::new(&data)
        .args(["--model", "auto", "--threads", "2"])
        .out(&out)
        .output();
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_report(&out);
    let (chosen, names) = choice(&r);
    assert_eq!(chosen, "led", "{}", r["model_choice"]);
    assert_eq!(r["model"], "led");
    assert_eq!(names[0], "led");
    // One latent number, and no incline: the fall stands for both constant-acceleration laws.
    let mut sorted = names.clone();
    sorted.sort();
    assert_eq!(
        sorted,
        [
            "damped-oscillator",
            "free-fall",
            "led",
            "pendulum",
            "torricelli"
        ]
    );
    // meta.json's truth still grades the chosen model's answer.
    let gamma = &r["parameters"][0];
    assert!(
        gamma["relative_error"].as_f64().unwrap().abs() < 0.02,
        "{gamma}"
    );
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("model chosen: led"), "{table}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        html.contains("Model chosen"),
        "report.html lacks the ranking"
    );
    // Progress names each candidate fitted.
    assert_eq!(
        stderr(&o).matches("model choice ").count(),
        5,
        "{}",
        stderr(&o)
    );
}

#[test]
fn candidate_files_are_refused_where_nothing_is_chosen() {
    let tmp = tempfile::tempdir().unwrap();
    let data = gen_dataset(
        &tmp.path().join("led"),
        "led",
        &["--samples", "4", "--size", "8"],
    );
    let toml = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/cooling.toml");
    let out = tmp.path().join("o");
    // The data set names its model: nothing is chosen.
    let o = Estimate::new(&data)
        .args(["--candidate", toml])
        .out(&out)
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--candidate"), "{}", stderr(&o));
    // A built-in model is no file.
    let o = Estimate::new(&data)
        .args(["--model", "auto", "--candidate", "led"])
        .out(&out)
        .output();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("model file"), "{}", stderr(&o));
    assert!(!out.join("report.json").exists());
}

#[test]
fn a_recordings_candidates_share_one_cut_from_the_motions_period() {
    if !util::need_ffmpeg() {
        return;
    }
    // A disc whose brightness swings every 31.4 frames, played at 20 fps (a period of 1.57 s).
    let tmp = tempfile::tempdir().unwrap();
    let (_, video) = oscillator_video(tmp.path(), 20);
    let out = tmp.path().join("auto");
    let o = Estimate::new(&video)
        .args(["--size", "20x15", "--epochs", "3", "--threads", "1"])
        .out(&out)
        .output();
    let r = read_report(&out);
    let cut = r["model_choice"]["cut"].as_str().unwrap_or_default();
    assert!(cut.contains("one period"), "{cut}\n{}", stderr(&o));
    // 31.4 frames a period over 19 gaps: stride 2, not any law's own Table 5 cut (the
    // oscillator's 0.2 s would be 4, the pendulum's 2 with clips of 20 frames, the tank's 20
    // shortened to fit).
    assert_eq!(r["recording"]["stride"], 2, "{cut}");
    assert_eq!(r["recording"]["frames_per_clip"], 20);
    let table = physvid_testkit::stdout(&o);
    assert!(table.contains("clips: every candidate"), "{table}");
}

#[test]
fn the_apis_choice_hands_back_the_chosen_models_clips() {
    if !util::need_ffmpeg() {
        return;
    }
    // Each candidate's clips are let go once its report is made; the chosen one's are loaded
    // again: the same clips its report was trained on.
    let tmp = tempfile::tempdir().unwrap();
    let (_, video) = oscillator_video(tmp.path(), 20);
    let mut req = estimator::Request::new(&video);
    req.load.recording.size = Some((20, 15));
    (req.training.epochs, req.training.threads, req.quiet) = (3, 1, true);
    let fit = estimator::estimation(&req).unwrap();
    let run = &fit.report.run;
    let choice = fit.report.model_choice.as_ref().expect("a model choice");
    assert_eq!(choice.chosen, run.model);
    assert!(choice.candidates.len() >= 2, "{:?}", choice.candidates);
    assert_eq!(fit.data.shape, run.shape);
    assert_eq!(fit.data.train.size()[0], run.train_clips);
    assert_eq!(fit.data.val.size()[0], run.validation_clips);
}
