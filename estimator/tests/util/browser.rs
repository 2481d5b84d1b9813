//! Headless Chromium for the tests that open a page: found on PATH (skipped with a message
//! where absent), run on a page with a time limit.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The first Chromium on PATH, or `None` with a message.
pub fn chromium() -> Option<PathBuf> {
    for name in ["chromium", "chromium-browser", "google-chrome", "chrome"] {
        let found = Command::new(name)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success());
        if found {
            return Some(PathBuf::from(name));
        }
    }
    physvid_testkit::require(
        "chromium",
        false,
        "scripts/setup.sh installs Debian's chromium for this test",
    );
    None
}

/// Runs headless Chromium on `page` with `mode` (`--dump-dom` or `--screenshot=PATH`, and any
/// other switch) and
/// returns its stdout (through a file: a page's DOM overfills a pipe); killed after 90 s.
pub fn headless(browser: &Path, page: &Path, mode: &[&str], profile: &Path) -> String {
    let stdout = profile.with_extension("stdout");
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--hide-scrollbars",
            "--window-size=1280,2000",
            "--virtual-time-budget=5000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(mode)
        .arg(format!("file://{}", page.display()))
        .stdout(std::fs::File::create(&stdout).unwrap())
        .stderr(Stdio::null())
        .spawn()
        .expect("chromium starts");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(90) {
            let _ = child.kill();
            panic!("chromium did not finish on {} in 90 s", page.display());
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    String::from_utf8_lossy(&std::fs::read(&stdout).unwrap()).into_owned()
}
