//! report.html and a batch's index.html opened in a real browser: headless Chromium loads each
//! page from disk (no network), its DOM must hold the estimates' rows and every image must have
//! decoded; a screenshot is taken. Skipped with a message where no Chromium is installed
//! (scripts/setup.sh installs Debian's `chromium` where it can).

mod util;

use std::path::Path;
use util::browser::{chromium, headless};
use util::{gen_dataset, read_report, real_video, Estimate};

/// Opens `page`: every image decoded, `needles` in the DOM; a screenshot that decodes, at the
/// window's width. Returns the DOM.
fn check_page(browser: &Path, page: &Path, needles: &[&str]) -> String {
    let dir = page.parent().unwrap();
    let profile = dir.join("chromium-profile");
    let dom = headless(browser, page, &["--dump-dom"], &profile);
    let images = dom.matches("<img ").count();
    let want = format!("data-images-decoded=\"{images}/{images}\"");
    if images > 0 {
        assert!(
            dom.contains(&want),
            "{}: not every image decoded",
            page.display()
        );
    }
    for n in needles {
        assert!(dom.contains(n), "{} lacks {n}", page.display());
    }
    let shot = dir.join("screenshot.png");
    headless(
        browser,
        page,
        &[&format!("--screenshot={}", shot.display())],
        &profile,
    );
    let img = image::open(&shot).expect("the screenshot decodes");
    assert_eq!(img.width(), 1280);
    eprintln!("screenshot of {}: {}", page.display(), shot.display());
    dom
}

#[test]
fn reports_and_the_batch_index_show_in_a_browser() {
    let Some(browser) = chromium() else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let set = gen_dataset(
        &tmp.path().join("set"),
        "intensity",
        &["--samples", "100", "--size", "32", "--seed", "2"],
    );
    let run = tmp.path().join("run");
    Estimate::new(&set)
        .args(["--epochs", "5"])
        .out(&run)
        .quiet()
        .ok();
    let report = read_report(&run);
    let dom = check_page(
        &browser,
        &run.join("report.html"),
        &[
            "gamma0",
            "gamma1",
            "1/s^2",
            "<pre id=\"command\">",
            "--epochs 5",
        ],
    );
    // One table row per reported value, as report.json has them.
    let rows = dom.matches("<tr class=\"estimate\">").count();
    assert_eq!(rows, report["parameters"].as_array().unwrap().len());
    assert_eq!(dom.matches("<img ").count(), 2, "parameters and latents");

    // A batch of two rows, one failing: the index links the good one's report.
    let file = tmp.path().join("runs.csv");
    std::fs::write(&file, format!("input\n{set}\nmissing.npy\n")).unwrap();
    let out = tmp.path().join("batch");
    let o = Estimate::bare()
        .arg("--batch")
        .arg(&file)
        .out(&out)
        .args(["--epochs", "3", "--quiet"])
        .output();
    assert_eq!(o.status.code(), Some(1));
    let dom = check_page(
        &browser,
        &out.join("index.html"),
        &["href=\"01-set/report.html\"", "missing.npy", "failed"],
    );
    assert_eq!(dom.matches("<tr class=\"row\">").count(), 2);
}

#[test]
fn a_recording_report_shows_its_timeline_and_clips_in_a_browser() {
    let Some(browser) = chromium() else {
        return;
    };
    let Some(video) = real_video("freefall-ball.mp4") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let run = tmp.path().join("run");
    Estimate::new(&video)
        .args(["--model", "free-fall", "--fps", "120", "--start", "3.933"])
        .args(["--end", "6.72", "--size", "16x160", "--epochs", "5"])
        .args(["--reference", "3.933s=0,6.7s=2.26"])
        .out(&run)
        .quiet()
        .estimated();
    let dom = check_page(
        &browser,
        &run.join("report.html"),
        &[
            "m/s^2",
            "Recording",
            "120.000 fps",
            "3.93300 s to 6.72000 s",
        ],
    );
    // Parameters, latents, the timeline, the picture's change with the span fitted, the
    // object's own track, the clips, and a frame of the recording to draw a stick on.
    assert_eq!(dom.matches("<img ").count(), 7);
    assert!(dom.contains("id=\"frame-svg\""), "the frame's stick tool");
    // The track drawn on the frame where the ball was seen (its first point inside the
    // 172×1716 portrait strip), its law's span over it; and as a picture of its own.
    let path = dom
        .split("id=\"track-path\" points=\"")
        .nth(1)
        .expect("the track drawn");
    let (x, y) = path.split(' ').next().unwrap().split_once(',').unwrap();
    let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
    assert!(
        (0.0..172.0).contains(&x) && (0.0..1716.0).contains(&y),
        "{x},{y}"
    );
    assert!(dom.contains("id=\"track-span\""));
    assert!(run.join("frame.jpg").exists());
    assert!(
        dom.contains("the span fitted (shaded)"),
        "the change figure's caption"
    );
    assert!(run.join("change.png").exists());
    // The second route: its section, its figure and its samples.
    assert!(
        dom.contains("Second route: the object's own track"),
        "the track's section"
    );
    assert!(dom.contains("id=\"track-line\""));
    assert!(run.join("track.png").exists());
    let csv = std::fs::read_to_string(run.join("track.csv")).unwrap();
    assert!(
        csv.starts_with("t_s,file_s,x_px,y_px,quality,along_px\n"),
        "{csv}"
    );
    assert!(csv.lines().count() > 20, "{csv}");
    assert!(
        !run.join("clips.png").exists(),
        "clips.png only with --preview"
    );
}
