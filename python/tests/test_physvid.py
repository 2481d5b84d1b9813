"""pytest tests of the Python package (python/): generate and estimate in process, the same
answers and files as the `gen` and `estimate` binaries, the object's track, a notebook's view,
typed errors, and docs/python.md's example. Run by scripts/test.sh after `cargo test` has built the binaries."""
import json
import os
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest
import torch

import physvid

ROOT = Path(__file__).resolve().parents[2]
BIN = ROOT / "target" / "release"


def cli(program, *args):
    return subprocess.run([str(BIN / program), *map(str, args)], capture_output=True, text=True)


@pytest.fixture(scope="module")
def small():
    # The estimator's own small set (estimator/tests/estimate_cli.rs).
    return physvid.generate("intensity", samples=200, size=32, seed=5)


def test_generate_then_estimate_recovers_gamma0_and_gamma1(small):
    assert small.frames.shape == (200, 20, 1, 32, 32) and small.frames.dtype == np.float32
    assert small.truth["gamma0"] == pytest.approx(4.0016)
    seen = []
    r = physvid.estimate(small, threads=2, progress=seen.append)
    # Each epoch of the training kept, in order, with the parameters by name.
    assert [e.epoch for e in seen] == list(range(1, r.report["epochs_run"] + 1))
    assert seen[-1].parameters.keys() == {"gamma0", "gamma1"} and seen[-1].most == 300
    assert r.model == "damped-oscillator" and "model_choice" not in r.report, "meta.json names it"
    g0, g1 = r.parameters["gamma0"], r.parameters["gamma1"]
    assert abs(g0.value / 4.0016 - 1) < 0.01, g0
    assert abs(g1.value / 0.08 - 1) < 0.10, g1
    assert g0.units == "SI" and g0.truth == pytest.approx(4.0016)
    assert r.verdict.grade == "ok", r.verdict
    assert len(r.history) == r.report["epochs_run"]
    # A notebook's view: the verdict and the values; no track on a data set.
    page = r._repr_html_()
    assert "verdict <b>ok</b>" in page and "<td>gamma0</td>" in page and f"{g0.value:.6g}" in page
    assert r.track is None
    # The figures: a panel a parameter, and the data set's frames.
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    fig = r.plot()
    assert len(fig.axes) == 2 and fig.axes[0].get_ylabel().startswith("gamma0")
    assert len(small.preview(clips=2, frames=5).axes) == 10


def swinging_disc(path, seconds=8.0, fps=30):
    """A bright disc on a grey wall oscillating along x, x = 40 + 15 cos(2π t) e^(−0.05 t), as a
    lossless video, or as PNG images where `path` is a folder's (`frame%03d.png` in it); ffmpeg
    reads the frames from a pipe."""
    import shutil

    if shutil.which("ffmpeg") is None:
        pytest.skip("ffmpeg is not installed (scripts/setup.sh installs it)")
    if path.suffix == "":
        path.mkdir()
        target = path / "frame%03d.png"
    else:
        target = path
    t = np.arange(int(seconds * fps)) / fps
    rows, cols = np.mgrid[0:60, 0:80]
    frames = np.full((len(t), 60, 80), 120, np.uint8)
    for k, s in enumerate(t):
        x = 40 + 15 * np.cos(2 * np.pi * s) * np.exp(-0.05 * s)
        frames[k][(cols - x) ** 2 + (rows - 30) ** 2 < 16] = 230
    done = subprocess.run(
        ["ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "gray", "-s", "80x60",
         "-r", str(fps), "-i", "-", *(["-c:v", "ffv1"] if path.suffix else []), str(target)],
        input=frames.tobytes(), capture_output=True,
    )
    assert done.returncode == 0, done.stderr
    return path


def test_the_same_answer_as_the_command_line_on_a_video_with_its_options(tmp_path):
    video = swinging_disc(tmp_path / "disc.mkv")
    flags = ["--model", "damped-oscillator", "--start", "1", "--end", "7", "--epochs", "15",
             "--threads", "2", "--stride", "2"]
    done = cli("estimate", video, *flags, "--out", tmp_path / "cli", "--quiet")
    assert done.returncode in (0, 4), done.stderr
    want = json.loads((tmp_path / "cli" / "report.json").read_text())
    kw = dict(model="damped-oscillator", start=1.0, end=7.0, epochs=15, threads=2, stride=2)
    try:
        got = physvid.estimate(video, progress=False, **kw)
    except physvid.UnreliableError as e:
        got = e.result
    assert [p["estimate"] for p in got.report["parameters"]] == [p["estimate"] for p in want["parameters"]]
    assert got.report["recording"]["start"] == want["recording"]["start"] == 1.0
    assert got.track is not None and len(got.track["t"]) == len(want["track"]["track"]["t"])
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    assert got.plot().axes[-1].get_xlabel() == "time (s)", "the track's panel"


def test_the_same_answer_as_the_command_line_on_an_image_folder(tmp_path):
    folder = swinging_disc(tmp_path / "frames", seconds=6.0)
    flags = ["--model", "damped-oscillator", "--fps", "30", "--epochs", "10", "--threads", "2"]
    done = cli("estimate", folder, *flags, "--out", tmp_path / "cli", "--quiet")
    assert done.returncode in (0, 4), done.stderr
    want = json.loads((tmp_path / "cli" / "report.json").read_text())
    try:
        got = physvid.estimate(folder, model="damped-oscillator", fps=30, epochs=10, threads=2,
                               progress=False)
    except physvid.UnreliableError as e:
        got = e.result
    assert [p["estimate"] for p in got.report["parameters"]] == [p["estimate"] for p in want["parameters"]]
    assert got.track is None, "an image folder has no track"


def test_every_option_of_the_command_line_is_a_keyword(small):
    done = cli("estimate", "--help")
    flags = set(re.findall(r"^\s+(?:-\w, )?(--[a-z0-9-]+)", done.stdout, re.M))
    elsewhere = {"--help", "--version", "--out", "--force", "--quiet", "--batch", "--shard", "--merge"}
    keywords = {o.flag for o in physvid.options().values()}
    assert len(flags) > 30 and flags - elsewhere == keywords, flags ^ (keywords | elsewhere)
    assert physvid.options()["incline_deg"].flag == "--incline-deg"
    assert physvid.options()["epochs"].default == "300" and not physvid.options()["preview"].takes_value
    # An unknown keyword names the close ones; a value the command line refuses, its message.
    with pytest.raises(TypeError, match="epochs"):
        physvid.estimate(small, epochz=3, progress=False)
    with pytest.raises(physvid.BadInputError, match="--stride"):
        physvid.estimate(small, stride="often", progress=False)


def test_track_follows_the_object_and_fits_its_law(tmp_path):
    table = physvid.track(swinging_disc(tmp_path / "disc.mkv"))
    assert table is not None
    columns = {c: np.asarray(table[c]) for c in ("t", "x", "y", "quality", "along")}
    assert len(columns["t"]) > 200 and np.all(np.diff(columns["t"]) > 0)
    # x follows the disc (displayed pixels, its centre 0.5 px in); y stays on its row.
    assert abs(columns["x"].max() - 55.5) < 1.5 and abs(np.median(columns["y"]) - 30.5) < 1.0
    about = table.attrs if hasattr(table, "attrs") else table
    assert about["chosen"] == "oscillation", about["laws"]
    # A round disc has no axis to read it by: its centroids (or its matches) are read.
    assert about["reading"] in ("centroids", "whole", "matches"), about["reading"]
    # A still camera's frames are read as shot.
    assert about["steadied"] is None, about["steadied"]
    law = next(l for l in about["laws"] if l["law"] == "oscillation")
    g0 = next(v["value"] for v in law["values"] if v["name"] == "gamma0")
    assert abs(g0 / (4 * np.pi**2 + 0.0025) - 1) < 0.01, g0
    # A trimmed span reads only its frames; a file that is no video is refused by name.
    assert physvid.track(tmp_path / "disc.mkv", start=4.0)["t"].__len__() < len(columns["t"])
    (tmp_path / "notes.txt").write_text("no video")
    with pytest.raises(physvid.BadInputError, match="notes.txt"):
        physvid.track(tmp_path / "notes.txt")


def test_the_same_answer_as_the_command_line_on_a_path_an_array_and_a_tensor(tmp_path, small):
    out = tmp_path / "cli"
    folder = small.save(tmp_path / "set")
    done = cli("estimate", folder, "--threads", "2", "--epochs", "30", "--out", out, "--quiet")
    assert done.returncode == 0, done.stderr
    want = {p["name"]: p["estimate"] for p in json.loads((out / "report.json").read_text())["parameters"]}
    # The saved folder, and the data set in memory (its meta.json naming the model and truth).
    for source in (folder, small):
        r = physvid.estimate(source, threads=2, epochs=30, progress=False)
        assert {n: p.value for n, p in r.parameters.items()} == want
        assert r.parameters["gamma0"].truth == small.truth["gamma0"]

    # A bare array: the CLI on the same values saved as .npy, with --dt.
    frames = small.frames[:120]
    npy = tmp_path / "clips.npy"
    np.save(npy, frames)
    flags = ["--model", "damped-oscillator", "--dt", small.dt, "--threads", "2", "--epochs", "30"]
    out = tmp_path / "cli-npy"
    done = cli("estimate", npy, *flags, "--out", out, "--quiet")
    assert done.returncode in (0, 4), done.stderr
    want = {p["name"]: p["estimate"] for p in json.loads((out / "report.json").read_text())["parameters"]}
    kw = dict(model="damped-oscillator", dt=small.dt, threads=2, epochs=30, progress=False)
    for source in (frames, torch.from_numpy(frames.copy())):
        try:
            got = physvid.estimate(source, **kw).report
        except physvid.UnreliableError as e:
            got = e.result.report
        assert {p["name"]: p["estimate"] for p in got["parameters"]} == want


def test_save_writes_what_gen_writes(tmp_path):
    done = cli("gen", "--scenario", "pendulum", "--samples", "12", "--size", "32", "--seed", "2",
               "--out", tmp_path / "gen")
    assert done.returncode == 0, done.stderr
    saved = physvid.generate("pendulum", samples=12, size=32, seed=2).save(tmp_path / "py")
    for name in ["frames.npy", "meta.json", "preview.png"]:
        assert (saved / name).read_bytes() == (tmp_path / "gen" / name).read_bytes(), name


def test_generate_writes_nothing_until_saved(tmp_path):
    import sys

    # In a process of its own whose temporary folder and working folder start empty.
    (tmp_path / "tmp").mkdir()
    (tmp_path / "here").mkdir()
    script = "import physvid; d = physvid.generate('led', samples=4, size=16); print(d.frames.shape)"
    env = dict(os.environ, TMPDIR=str(tmp_path / "tmp"))
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path / "here", env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("(4, "), done.stdout
    assert list((tmp_path / "tmp").iterdir()) == [] and list((tmp_path / "here").iterdir()) == []


def test_out_and_save_write_what_estimate_writes(tmp_path, small):
    out = tmp_path / "run"
    r = physvid.estimate(small, threads=2, epochs=5, progress=False, out=out)
    saved = r.save(tmp_path / "saved")
    folder = small.save(tmp_path / "set")
    done = cli("estimate", folder, "--threads", "2", "--epochs", "5", "--out", tmp_path / "cli", "--quiet")
    assert done.returncode == 0, done.stderr
    for name in ["report.json", "report.html", "metrics.csv", "parameters.png", "latents.png"]:
        assert (out / name).is_file() and (saved / name).is_file(), name
    for folder in (out, saved):
        mine = json.loads((folder / "report.json").read_text())
        theirs = json.loads((tmp_path / "cli" / "report.json").read_text())
        assert [p["estimate"] for p in mine["parameters"]] == [p["estimate"] for p in theirs["parameters"]]
    # The same run built step by step: the same answer.
    req = physvid.Request(small, threads=2)
    req.epochs = 5
    assert req.epochs == 5 and req.seed is None and req.resolved()["training"]["epochs"] == 5
    assert req.resolved()["training"]["seed"] == 0  # the default, from the command line's parser
    with pytest.raises(TypeError, match="epochs"):
        req.epochz = 3
    again = req.run(progress=False)
    assert {n: p.value for n, p in again.parameters.items()} == {n: p.value for n, p in r.parameters.items()}
    assert (saved / "metrics.csv").read_text().splitlines()[0] == (tmp_path / "cli" / "metrics.csv").read_text().splitlines()[0]
    # A folder this tool did not make, not empty: refused, as by the command line.
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "notes.txt").write_text("mine")
    with pytest.raises(physvid.BadInputError, match="force"):
        r.save(tmp_path / "mine")


def test_errors_are_typed_and_name_the_input(tmp_path):
    with pytest.raises(physvid.BadInputError, match="missing.npy"):
        physvid.estimate(tmp_path / "missing.npy", dt=0.1, progress=False)
    with pytest.raises(physvid.BadInputError, match="wobble"):
        physvid.estimate(tmp_path, model="wobble", progress=False)
    with pytest.raises(physvid.BadInputError, match="scenario"):
        physvid.generate("wobble")
    with pytest.raises(physvid.BadInputError, match="N, T, C, H, W"):
        physvid.estimate(np.zeros((4, 4), np.float32), dt=0.1, progress=False)
    # Frames shuffled within each clip: the verdict calls the answer unreliable.
    frames = physvid.generate("intensity", samples=80, size=32, seed=1).frames.copy()
    rng = np.random.default_rng(0)
    for clip in frames:
        rng.shuffle(clip)
    with pytest.raises(physvid.UnreliableError) as e:
        physvid.estimate(frames, model="damped-oscillator", dt=0.2, threads=2, epochs=20, progress=False)
    assert json.loads(e.value.args[1])["verdict"]["grade"] == "unreliable"
    assert e.value.result.verdict.grade == "unreliable"
    assert issubclass(physvid.UnreliableError, physvid.PhysvidError)


def test_the_documented_example_runs():
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks, "docs/python.md has a python example"
    exec(compile(blocks[0], "docs/python.md", "exec"), {})


def test_the_worked_example_on_a_recording_runs(tmp_path, monkeypatch):
    recording = ROOT.parent / "shared" / "real-videos" / "spring-k525.mp4"
    if not recording.exists():
        pytest.skip(f"{recording} is absent (the shared recordings)")
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 2, "docs/python.md has a worked example on a recording"
    (tmp_path / "spring-k525.mp4").symlink_to(recording)
    monkeypatch.chdir(tmp_path)
    exec(compile(blocks[1], "docs/python.md", "exec"), {})
    assert (tmp_path / "spring-k525.png").stat().st_size > 10_000


def test_ctrl_c_stops_training_promptly_and_writes_nothing(tmp_path):
    import signal
    import sys
    import time

    data = physvid.generate("intensity", samples=1000, size=64, seed=2).save(tmp_path / "set")
    out = tmp_path / "run"
    # Python's own Ctrl-C handler, even where this test runs with SIGINT ignored (a background
    # job), as it is in a terminal.
    script = (
        "import physvid, signal, sys\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "try:\n"
        "    say = lambda e: print('epoch', e.epoch, file=sys.stderr, flush=True)\n"
        f"    physvid.estimate({str(data)!r}, threads=1, out={str(out)!r}, progress=say)\n"
        "except KeyboardInterrupt:\n"
        "    sys.exit(130)\n"
    )
    child = subprocess.Popen([sys.executable, "-c", script], stderr=subprocess.PIPE, text=True)
    # The first line comes after the first epoch of the training kept.
    for line in child.stderr:
        if line.startswith("epoch"):
            break
    assert child.poll() is None, "still training"
    sent = time.time()
    child.send_signal(signal.SIGINT)
    code = child.wait(timeout=60)
    assert code == 130, child.stderr.read()
    assert time.time() - sent < 5, "stopped within an epoch or two"
    assert not (out / "report.json").exists()
