//! `--stick` end to end: a ball tossed across a rendered picture, and one dropped, read in
//! metres by a length in the picture; and the stick's refusals (no length, a point off the
//! frame, an input with no track). The report's frame, in a browser: the stick drawn, and two
//! clicks that give one. The shared toss and roll, where present, read with their sticks.

mod util;

use std::path::{Path, PathBuf};
use util::{browser, read_report, stderr, track_law, Estimate};

const FPS: u32 = 30;
const FRAMES: usize = 40;
/// The picture's width and height (pixels).
const SIZE: (u32, u32) = (240, 200);
/// The toss: across at 60 px/s, up at 40 px/s, falling at 100 px/s².
const DOWN: f64 = 100.0;
/// A stick 101.94 px long for 10 m: 10.194 px a metre, so the fall's 100 px/s² is 9.81 m/s².
const STICK: &str = "0,0:0,101.94=10";

/// The ball's centre at frame k.
fn ball(k: usize) -> (f64, f64) {
    let t = k as f64 / FPS as f64;
    (30.0 + 60.0 * t * 2.0, 60.0 - 40.0 * t + 0.5 * DOWN * t * t)
}

/// A drop: the ball held at rest until 0.2 s, then falling at twice the toss's 100 px/s².
fn dropped(k: usize) -> (f64, f64) {
    let t = (k as f64 / FPS as f64 - 0.2).max(0.0);
    (120.0, 30.0 + DOWN * t * t)
}

/// The toss as a lossless grey video: a light ball of radius 5 on a dark wall.
fn toss(dir: &Path) -> PathBuf {
    render(dir, ball)
}

/// The ball at `centre(k)` in frame k as a lossless grey video.
fn render(dir: &Path, centre: fn(usize) -> (f64, f64)) -> PathBuf {
    util::ball_video(dir, SIZE, FRAMES, FPS, centre)
}

#[test]
fn a_stick_reads_the_toss_in_metres_and_calibrates_the_latent_by_it() {
    if !util::need_ffmpeg() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let v = toss(tmp.path());
    let out = tmp.path().join("run");
    let o = Estimate::new(&v)
        .args(["--stick", STICK, "--epochs", "10", "--threads", "1"])
        .out(&out)
        .output();
    let err = stderr(&o);
    assert!(matches!(o.status.code(), Some(0 | 4)), "{err}");
    let report = read_report(&out);
    let track = &report["track"];
    assert_eq!(track["chosen"], "constant-acceleration", "{track}");
    assert_eq!(track["stick"]["metres"], 10.0);
    let law = track_law(&report, "constant-acceleration");
    let si = &law["si"][0];
    assert_eq!(
        (&si["name"], &si["unit"]),
        (&"acceleration".into(), &"m/s^2".into())
    );
    let a = si["value"].as_f64().unwrap();
    assert!((a / 9.81 - 1.0).abs() < 0.01, "the track's {a} m/s²");
    // The latent route: the fall its direction names (no model choice), calibrated by the
    // track's positions in metres.
    assert_eq!(report["model"], "free-fall");
    assert!(report["model_choice"].is_null());
    assert!(
        err.contains("calibrated it by the track's 6 positions in metres"),
        "{err}"
    );
    assert_eq!(report["calibration"]["source"], "flags");
    // The page names the stick and its scale beside the track.
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        html.contains("id=\"track-stick\"") && html.contains("--stick 0,0:0,101.94=10"),
        "no stick on the page"
    );
    clicks_give_a_stick(&out.join("report.html"));
}

/// Opens `page` in a browser inside a page that clicks two points of its frame and types a
/// length: the stick given is drawn on the frame, and the tool writes the flag for the clicks.
fn clicks_give_a_stick(page: &Path) {
    let Some(browser) = browser::chromium() else {
        return;
    };
    let dir = page.parent().unwrap();
    let harness = dir.join("clicks.html");
    std::fs::write(
        &harness,
        r##"<!DOCTYPE html><html><body><iframe id="f" src="report.html" width="1200" height="3000"></iframe>
<script>
document.getElementById("f").addEventListener("load", function () {
  var d = this.contentDocument, svg = d.getElementById("frame-svg"), b = svg.getBoundingClientRect();
  var w = +svg.getAttribute("data-width"), h = +svg.getAttribute("data-height");
  var at = [];
  function click(x, y) {
    // A mouse event's position is whole CSS pixels: where that puts the click in the frame.
    var cx = Math.round(b.left + x * b.width / w), cy = Math.round(b.top + y * b.height / h);
    at.push([(cx - b.left) * w / b.width, (cy - b.top) * h / b.height]);
    svg.dispatchEvent(new MouseEvent("click", { bubbles: true, clientX: cx, clientY: cy }));
  }
  click(40, 20);
  click(200, 180);
  document.body.setAttribute("data-at", JSON.stringify(at));
  var m = d.getElementById("stick-metres");
  m.value = "0.5";
  m.dispatchEvent(new Event("input"));
  document.body.setAttribute("data-stick", d.getElementById("stick-text").textContent);
  document.body.setAttribute("data-given", d.querySelectorAll("#stick-given line").length);
  document.body.setAttribute("data-drawn", d.querySelectorAll("#stick-new circle").length);
});
</script></body></html>"##,
    )
    .unwrap();
    let dom = browser::headless(
        &browser,
        &harness,
        &["--allow-file-access-from-files", "--dump-dom"],
        &dir.join("chromium-profile"),
    );
    let attr = |name: &str| -> String {
        let from = dom.find(&format!("{name}=\"")).expect(name) + name.len() + 2;
        dom[from..from + dom[from..].find('"').unwrap()].replace("&quot;", "\"")
    };
    // The two clicks, where the mouse's whole pixels put them (within a page pixel of the
    // points aimed at: the frame is shown at its own size), read back to the half pixel.
    let at: Vec<(f64, f64)> = serde_json::from_str(&attr("data-at")).unwrap();
    let half = |v: f64| (v * 2.0).round() / 2.0;
    let want = format!(
        "--stick {},{}:{},{}=0.5",
        half(at[0].0),
        half(at[0].1),
        half(at[1].0),
        half(at[1].1)
    );
    assert_eq!(attr("data-stick"), want, "{}", &dom[..dom.len().min(300)]);
    for ((x, y), aim) in at.iter().zip([(40.0, 20.0), (200.0, 180.0)]) {
        assert!(
            (x - aim.0).abs() <= 1.0 && (y - aim.1).abs() <= 1.0,
            "{at:?}"
        );
    }
    assert!(dom.contains(r#"data-given="1""#) && dom.contains(r#"data-drawn="2""#));
}

#[test]
fn a_drop_by_a_stick_gives_g() {
    if !util::need_ffmpeg() {
        return;
    }
    // 200 px/s² on a stick of 20.388 px a metre: 9.81 m/s². Issue 64's bar for a drop on a
    // recording: within 3 %, the track's and the latent's.
    let tmp = tempfile::tempdir().unwrap();
    let v = render(tmp.path(), dropped);
    let out = tmp.path().join("run");
    let o = Estimate::new(&v)
        .args(["--stick", "0,0:0,101.94=5", "--threads", "1"])
        .out(&out)
        .output();
    let err = stderr(&o);
    assert!(matches!(o.status.code(), Some(0 | 4)), "{err}");
    let report = read_report(&out);
    assert_eq!(report["model"], "free-fall", "{err}");
    let track = util::track_si(&report);
    assert!(
        (track / 9.81 - 1.0).abs() < 0.01,
        "the track's {track} m/s²"
    );
    let g = util::estimate_of(&report, "g");
    assert!((g / 9.81 - 1.0).abs() < 0.03, "the latent's g {g}: {err}");
    assert_ne!(report["verdict"]["grade"], "unreliable", "{err}");
    // Square to the camera: the track's halves agree, and no perspective is named.
    let verdict = report["verdict"].to_string();
    assert!(!verdict.contains("--plane"), "{verdict}");
}

#[test]
fn a_stick_that_is_no_length_off_the_frame_or_on_no_video_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("data");
    util::gen_dataset(&data, "intensity", &[]);
    let o = Estimate::new(&data)
        .args(["--stick", "1,1:2,1=1"])
        .out(&tmp.path().join("a"))
        .output();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("px apart"), "{}", stderr(&o));
    let o = Estimate::new(&data)
        .args(["--stick", STICK, "--epochs", "1"])
        .out(&tmp.path().join("b"))
        .output();
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("in a video file"), "{}", stderr(&o));
    if !util::need_ffmpeg() {
        return;
    }
    let v = toss(tmp.path());
    let out = tmp.path().join("c");
    let o = Estimate::new(&v)
        .args(["--stick", "0,0:0,300=1", "--epochs", "1"])
        .out(&out)
        .output();
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("outside the 240×200 frame"),
        "{}",
        stderr(&o)
    );
    assert!(!out.join("report.json").exists());
}

/// The track's acceleration in SI on a shared recording read with its stick (its README's two
/// points and length), and the report's grade.
fn on_shared(name: &str, extra: &[&str]) -> Option<serde_json::Value> {
    let v = util::real_video(name)?;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("run");
    let o = Estimate::new(&v).args(extra).out(&out).output();
    assert!(matches!(o.status.code(), Some(0 | 4)), "{}", stderr(&o));
    Some(read_report(&out))
}

#[test]
fn the_shared_toss_and_roll_read_with_their_sticks() {
    // The toss past its metre stick (400 px a metre): read as a fall by its direction, the
    // latent's g within issue 64's bar of 4 % of 9.80, not unreliable; the track followed over
    // the toss's longest span where a constant acceleration holds (its later part alone, read
    // where the ball blurs most, gave 10.24).
    if let Some(r) = on_shared("toss-tracker.mp4", &["--stick", "284,45.5:284,446=1"]) {
        assert!(util::track_si(&r).is_finite(), "no acceleration in m/s²");
        assert_eq!(r["model"], "free-fall");
        let g = util::estimate_of(&r, "g");
        assert!((g / 9.80 - 1.0).abs() < 0.04, "the latent's g {g}");
        assert_ne!(r["verdict"]["grade"], "unreliable");
    }
    // The 10.3° roll between marks 1 m apart: 0.843 m/s², the latent's answer calibrated by
    // the track and not held against by the verdict.
    let roll = ["--stick", "64,294:582,407=1", "--incline-deg", "10.3"];
    if let Some(r) = on_shared("incline-roll10.avi", &roll) {
        let a = util::estimate_of(&r, "acceleration");
        assert!((a / 0.843 - 1.0).abs() < 0.04, "the latent's a {a}");
        assert_ne!(r["verdict"]["grade"], "unreliable");
    }
}
