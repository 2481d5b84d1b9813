#!/usr/bin/env python3
"""Tanks draining and LEDs dimming, filmed as videos: `gen`'s Delfys75 scenes (Table 4's three
settings each) rendered as one long clip, 128×128, encoded as h264 (crf 18), and estimated as
README's users would: the file, and for a tank three heights read from the render's calibration
(`--reference`), no model named. Drawn (2026-12-01) with the tank's drain law on the brightness
of what changes (`estimator/src/track/laws/drain.rs`): a drain over three quarters of its level
guides the tank alone, and its k in metres from the empty time and the heights read
(`estimator/src/track/tank.rs`) is the answer where it is the more precise; an LED's light must
keep its decay. Truths: the render's k or γ.

usage: tanks_suite.py ESTIMATE OUT_DIR [--md FILE]
"""
import json, os, subprocess, sys, time
import numpy as np
from suite_table import arguments, finish

TOLERANCE = 0.02  # the real recordings' bar for a rate

# (scene, setting, frames, dt): a tank from 0.07 m to 0.01 m at most; an LED over 6–7 e-folds.
SCENES = [("torricelli", 1, 300, 0.1), ("torricelli", 2, 240, 0.1), ("torricelli", 3, 190, 0.1),
          ("led", 1, 300, 0.01), ("led", 2, 300, 0.02), ("led", 3, 300, 0.04)]


def render(gen, folder, video, scene, setting, frames, dt):
    """The scene rendered by `gen` into `folder`, its one clip encoded to `video`; its meta."""
    subprocess.run([gen, "--scenario", scene, "--setting", str(setting), "--samples", "1",
                    "--frames", str(frames), "--dt", str(dt), "--size", "128", "--seed",
                    str(setting), "--out", folder, "--force"], check=True, capture_output=True)
    clip = np.load(os.path.join(folder, "frames.npy"))[0, :, 0]
    h, w = clip.shape[1:]
    pixels = (np.clip(clip, 0, 1) * 255).round().astype(np.uint8)
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "gray", "-s",
                    f"{w}x{h}", "-r", str(1 / dt), "-i", "-", "-c:v", "libx264", "-pix_fmt",
                    "yuv420p", "-crf", "18", video], input=pixels.tobytes(), check=True)
    return json.load(open(os.path.join(folder, "meta.json")))


def readings(meta):
    """Three heights from the render's calibration: its first, middle and last point."""
    pts = sorted(meta["calibration"]["reference_points"], key=lambda p: p["frame"])
    pick = [pts[0], pts[len(pts) // 2], pts[-1]]
    return ",".join(f"{p['frame'] * meta['dt']:.1f}s={p['value']:.6f}" for p in pick)


def main():
    a = arguments(__doc__)
    gen = os.path.join(os.path.dirname(os.path.abspath(a.estimate)), "gen")
    started = time.time()
    rows = []
    for scene, setting, frames, dt in SCENES:
        name = f"{scene} {setting}"
        folder = os.path.join(a.out, f"{scene}{setting}")
        video = folder + ".mp4"
        meta = render(gen, folder, video, scene, setting, frames, dt)
        (value_name, truth), = meta["model"]["parameters"].items()
        run = os.path.join(a.out, f"run-{scene}{setting}")
        extra = ["--reference", readings(meta)] if scene == "torricelli" else []
        began = time.time()
        subprocess.run([a.estimate, video, *extra, "--seed", "0", "--threads", "2", "--out", run,
                        "--force", "--quiet"], capture_output=True)
        seconds = time.time() - began
        r = json.load(open(os.path.join(run, "report.json")))
        p = next(p for p in r["parameters"] if p["name"] == value_name)
        routes = p.get("routes") or {}
        t = r.get("track") or {}
        chosen = t.get("chosen", "–")
        checks = ", ".join(x["check"] for x in r["verdict"]["reasons"]) or "–"
        rows.append((name, value_name, truth, chosen, routes.get("track"), routes.get("latent",
                     p["estimate"]), p["estimate"], r["model"], bool(r.get("model_choice")),
                     r["verdict"]["grade"], checks, seconds))
        print(f"{name}: {r['model']} {p['estimate']:.5g} ({truth}) {r['verdict']['grade']}",
              file=sys.stderr)
    right = lambda r: r[7] == r[0].split()[0] and abs(r[6] / r[2] - 1) <= TOLERANCE
    lines = [
        "# Tanks and LEDs filmed (`scripts/tanks_suite.py`)",
        "",
        "`gen`'s scenes as videos (see the script's docstring); `estimate VIDEO`, a tank with "
        "three heights read, no model named. Track: the law the brightness of what changes "
        "follows; track k: the tank's k in metres from its empty time and the heights; latent: "
        "the latent route's; answer: the reported value (the track's where its error is the "
        "smaller, `guide::tank`); chosen by: the track's law (guided) or a choice among every "
        "model.",
        "",
        "| scene | value | truth | track's law | track | latent | answer | error | model "
        "| chosen by | grade | checks | run (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    fmt = lambda v: "–" if v is None else f"{v:.5g}"
    for (name, value_name, truth, chosen, track, latent, answer, model, choice, grade, checks,
         seconds) in rows:
        lines.append(f"| {name} | {value_name} | {truth} | {chosen} | {fmt(track)} | "
                     f"{fmt(latent)} | {answer:.5g} | {100 * (answer / truth - 1):+.2f} % | "
                     f"{model} | {'a choice' if choice else 'the track'} | {grade} | {checks} | "
                     f"{seconds:.1f} |")
    wrong_ok = sum(not right(r) and r[9] == "ok" for r in rows)
    lines += [
        "",
        f"Right model and within {100 * TOLERANCE:.0f} %: {sum(map(right, rows))} of "
        f"{len(rows)}; otherwise and graded ok: {wrong_ok}.",
    ]
    finish(lines, "tanks_suite.py", started, a.md)


if __name__ == "__main__":
    main()
