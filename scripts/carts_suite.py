#!/usr/bin/env python3
"""Carts pulled from rest along a level track, rendered the way someone else would film them
(numpy only, not gen's code), and estimated as README's users would: the file and three
readings of the distance along the track, no model named.

A uniform dark cart (60×30 pixels, larger than the track's template patch: matched by its
middle, it is placed along the rail only by its blob) rests at x = 90 px on a rail for 0.5 s,
then is pulled at a constant acceleration (400 px a metre), filmed for 3 s at 30 fps on a wall
of coarse grey texture, ±2 grey levels of noise; some with a string over a pulley to a hanging
mass that falls beside it (a second thing that moves), some encoded as a phone stores them
(h264, whole-pixel positions), some pulled hard enough to leave the frame. Drawn (2026-12-01)
after a cart showed the track's constant acceleration taking in the frames of rest before the
release (`estimator/src/track/release.rs`) and its noisier reading chosen for holding its
law longer (`estimator/src/track/object.rs`); every scene's truth is the acceleration drawn.
Readings: 0 at the release (0.5 s), and the distances drawn at 1.5 s and 2.0 s.

usage: carts_suite.py ESTIMATE OUT_DIR [--md FILE]
"""
import json, os, subprocess, sys, time
import numpy as np
from suite_table import arguments, finish

W, H, FPS, SECONDS, PER_METRE, RELEASE = 640, 360, 30, 3.0, 400.0, 0.5
TOLERANCE = 0.03  # the falls suite's bar

SCENES = {
    "lossless": dict(a=0.3),
    "phone-encoded": dict(a=0.3, h264=True),
    "lossless, leaves the frame": dict(a=0.6),
    "phone-encoded, leaves the frame": dict(a=0.6, h264=True),
    "hanging mass in view, phone-encoded": dict(a=0.15, hang=True, h264=True),
    "hanging mass in view, lossless, noise 6": dict(a=0.15, hang=True, noise=6.0),
}


def render(path, a, h264=False, hang=False, noise=2.0):
    """The scene at acceleration `a` (m/s²) written to `path`."""
    codec = ["-c:v", "libx264", "-crf", "18", "-pix_fmt", "yuv420p"] if h264 else ["-c:v", "ffv1"]
    p = subprocess.Popen(["ffmpeg", "-y", "-v", "error", "-f", "rawvideo", "-pix_fmt", "gray",
                          "-s", f"{W}x{H}", "-r", str(FPS), "-i", "-", *codec, path],
                         stdin=subprocess.PIPE)
    rng = np.random.default_rng(0)
    blocks = np.random.default_rng(7).normal(0, 1, (H // 8 + 1, W // 8 + 1))
    wall = 200.0 + np.kron(blocks, np.ones((8, 8)))[:H, :W] * 25
    wall[180:240] = 200.0
    xx = np.arange(W)
    for k in range(int(SECONDS * FPS)):
        s = 0.5 * a * max(0.0, k / FPS - RELEASE) ** 2 * PER_METRE
        img = wall.copy()
        img[230:236] = 90.0  # the rail
        x0 = 60.0 + s
        if h264:  # whole pixels, as a phone's encoder smears a subpixel edge anyway
            img[200:230, int(x0):int(x0) + 60] = 40.0
        else:  # each column covered in part at the cart's edges
            cover = np.clip(np.minimum(xx + 1 - x0, x0 + 60 - xx), 0, 1)
            img[200:230] = img[200:230] * (1 - cover) + 40.0 * cover
        if hang:
            img[150:153, int(x0) + 60:600] = 60.0  # the string
            y0 = int(160 + s)
            img[140:150, 595:605] = 70.0  # the pulley
            img[y0:y0 + 30, 590:610] = 50.0  # the hanging mass
        img += rng.normal(0, noise, img.shape)
        p.stdin.write(np.clip(img, 0, 255).astype(np.uint8).tobytes())
    p.stdin.close()
    p.wait()


def main():
    a = arguments(__doc__)
    started = time.time()
    rows = []
    for i, (name, spec) in enumerate(SCENES.items()):
        acc = spec["a"]
        video = os.path.join(a.out, f"cart{i}.{'mp4' if spec.get('h264') else 'mkv'}")
        render(video, acc, spec.get("h264", False), spec.get("hang", False),
               spec.get("noise", 2.0))
        at = lambda t: 0.5 * acc * (t - RELEASE) ** 2
        refs = f"{RELEASE}s=0,1.5s={at(1.5):.4f},2.0s={at(2.0):.4f}"
        run = os.path.join(a.out, f"run{i}")
        subprocess.run([a.estimate, video, "--reference", refs, "--seed", "0", "--out", run,
                        "--force", "--quiet"], capture_output=True)
        r = json.load(open(os.path.join(run, "report.json")))
        answer = next(p["estimate"] for p in r["parameters"] if p["name"] == "acceleration")
        t = r.get("track") or {}
        law = next((l for l in t.get("laws", []) if l["law"] == t.get("chosen")), None)
        value = lambda vs, n: next((v["value"] for v in vs if v["name"] == n), None)
        track = law and value(law.get("si", []), "acceleration")
        vertex = law and value(law["values"], "vertex")
        reading = (t.get("track") or {}).get("reading", "–")
        # The latent's own value where the answer is the track's (`guide::acceleration`).
        routes = next(p for p in r["parameters"] if p["name"] == "acceleration").get("routes")
        latent = routes["latent"] if routes else answer
        checks = ", ".join(x["check"] for x in r["verdict"]["reasons"]) or "–"
        rows.append((name, acc, vertex, reading, track, latent, answer, r["model"],
                     r["verdict"]["grade"], checks))
        print(f"{name}: {r['model']} {answer:.4f} track {track} {r['verdict']['grade']}",
              file=sys.stderr)
    right = lambda r: r[7] == "sliding-block" and abs(r[6] / r[1] - 1) <= TOLERANCE
    lines = [
        "# Carts pulled from rest (`scripts/carts_suite.py`)",
        "",
        "Rendered by numpy, not gen (see the script's docstring); `estimate VIDEO --reference` "
        "with three readings (at rest at the release, and two in the motion), no model named. "
        "Release: the vertex of the constant acceleration the track holds (drawn at 0.5 s); "
        "track: its acceleration in metres by the readings; latent: the latent route's; answer: "
        "the reported acceleration (the track's where its error is the smaller, "
        "`guide::acceleration`, else the latent's).",
        "",
        "| scene | drawn a (m/s²) | release read (s) | track read by | track a | latent a "
        "| answer | error | model | grade | checks |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    fmt = lambda v, spec: "–" if v is None else format(v, spec)
    for name, acc, vertex, reading, track, latent, answer, model, grade, checks in rows:
        err = 100 * (answer / acc - 1)
        off = lambda v: "" if v is None else f" ({100 * (v / acc - 1):+.2f} %)"
        lines.append(f"| {name} | {acc} | {fmt(vertex, '.4f')} | {reading} | "
                     f"{fmt(track, '.5f')}{off(track)} | {latent:.5f}{off(latent)} | "
                     f"{answer:.5f} | {err:+.2f} % | {model} | {grade} | {checks} |")
    wrong_ok = sum(not right(r) and r[8] == "ok" for r in rows)
    lines += [
        "",
        f"Answer within {100 * TOLERANCE:.0f} %: {sum(map(right, rows))} of {len(rows)}; "
        f"outside it and graded ok: {wrong_ok}.",
    ]
    finish(lines, "carts_suite.py", started, a.md)


if __name__ == "__main__":
    main()
