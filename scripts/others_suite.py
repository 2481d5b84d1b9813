#!/usr/bin/env python3
"""A robustness suite rendered the way another group would (numpy only, not gen's code).

A black rod-and-bob pendulum whose angle obeys theta'' + 0.08 theta' + 4.0016 theta = 0 from
60 degrees (the ICML 2026 peer's set-up: 64x64 grey, 20 fps, 157 frames), under conditions at
levels 1..5: noise background, moving clutter, camera shake, brightness drift, moving light
with shadow, occluder, gaussian noise. Each video is written as NAME.npy (every 20-frame
window, [N, 20, 1, 64, 64], dt 0.05) and, with --mp4, NAME.mp4 (ffmpeg, lossless-ish).

usage: others_suite.py OUT [--conditions clean,shake,...] [--levels 1,3,5] [--mp4] [--seed S]
"""
import argparse, json, os, subprocess
import numpy as np

SIZE, FPS, FRAMES, SS = 64, 20.0, 157, 4
G0, G1, THETA0 = 4.0016, 0.08, np.deg2rad(60.0)


def theta(t):
    z, w = G1 / 2, np.sqrt(G0 - (G1 / 2) ** 2)
    return THETA0 * np.exp(-z * t) * (np.cos(w * t) + z / w * np.sin(w * t))


def grid():
    c = (np.arange(SIZE * SS) + 0.5) / SS
    return np.meshgrid(c, c)  # x, y


X, Y = grid()


def down(img):
    return img.reshape(SIZE, SS, SIZE, SS).mean(axis=(1, 3))


def segment_mask(x0, y0, x1, y1, half):
    dx, dy = x1 - x0, y1 - y0
    L2 = dx * dx + dy * dy
    u = np.clip(((X - x0) * dx + (Y - y0) * dy) / L2, 0, 1)
    d2 = (X - x0 - u * dx) ** 2 + (Y - y0 - u * dy) ** 2
    return d2 <= half * half


def disc_mask(cx, cy, r):
    return (X - cx) ** 2 + (Y - cy) ** 2 <= r * r


def render(cond, level, seed):
    rng = np.random.default_rng(seed)
    t = np.arange(FRAMES) / FPS
    th = theta(t)
    px, py, L, rb = 32.0, 14.0, 26.0, 5.0
    bg_level = 0.85
    background = np.full((SIZE * SS, SIZE * SS), bg_level)
    if cond == "texture":
        # Smooth random texture, contrast grows with level.
        tex = rng.standard_normal((SIZE // 4, SIZE // 4))
        tex = np.kron(tex, np.ones((4 * SS, 4 * SS)))
        k = np.ones(9 * SS) / (9 * SS)
        tex = np.apply_along_axis(lambda r: np.convolve(r, k, "same"), 1, tex)
        tex = np.apply_along_axis(lambda r: np.convolve(r, k, "same"), 0, tex)
        tex /= tex.std() + 1e-9
        background = np.clip(bg_level + 0.06 * level * tex, 0, 1)
    clutter = []
    if cond == "clutter":
        for _ in range(level):
            clutter.append(dict(x=rng.uniform(5, 59), y=rng.uniform(5, 59), vx=rng.uniform(-12, 12),
                                vy=rng.uniform(-12, 12), r=rng.uniform(3, 6), g=rng.uniform(0.2, 0.6)))
    occ = None
    if cond == "occlusion":
        # A grey bar covering part of the swing; wider with level.
        w = 4 + 4 * level
        occ = (32 + 8 - w / 2, 32 + 8 + w / 2)
    out = np.empty((FRAMES, SIZE, SIZE), np.float32)
    shake = np.zeros((FRAMES, 2))
    if cond == "shake":
        shake = rng.normal(0, 0.6 * level, (FRAMES, 2))
    for k in range(FRAMES):
        img = background.copy()
        ox, oy = shake[k]
        bx, by = px + L * np.sin(th[k]), py + L * np.cos(th[k])
        if cond == "light":
            # A light circling the scene: a soft brightness gradient and the pendulum's shadow.
            a = 2 * np.pi * k / FRAMES * (0.5 + 0.3 * level)
            lx, ly = np.cos(a), np.sin(a)
            img = img * (1 + 0.08 * level * ((X - 32) * lx + (Y - 32) * ly) / 32)
            sx, sy = 3 * lx * level / 2, 3 * ly * level / 2 + 2
            sh = segment_mask(px + sx + ox, py + sy + oy, bx + sx + ox, by + sy + oy, 1.2) | disc_mask(bx + sx + ox, by + sy + oy, rb)
            img = np.where(sh, img * (1 - 0.1 * level), img)
        for c in clutter:
            cx = (c["x"] + c["vx"] * t[k]) % 64
            cy = (c["y"] + c["vy"] * t[k]) % 64
            img = np.where(disc_mask(cx, cy, c["r"]), c["g"], img)
        m = segment_mask(px + ox, py + oy, bx + ox, by + oy, 1.0) | disc_mask(bx + ox, by + oy, rb)
        img = np.where(m, 0.05, img)
        if occ is not None:
            img = np.where((X >= occ[0]) & (X <= occ[1]) & (Y > 20), 0.55, img)
        f = down(img)
        if cond == "drift":
            f = f * (1 - 0.08 * level * np.sin(2 * np.pi * t[k] / 5.3)) + 0.03 * level * t[k] / t[-1]
        if cond == "noise":
            f = f + rng.normal(0, 0.04 * level, f.shape)
        out[k] = np.clip(f, 0, 1)
    return out, th


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--conditions", default="clean,texture,clutter,shake,drift,light,occlusion,noise")
    ap.add_argument("--levels", default="1,2,3,4,5")
    ap.add_argument("--mp4", action="store_true")
    ap.add_argument("--seed", type=int, default=7)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    for cond in a.conditions.split(","):
        for level in ([0] if cond == "clean" else [int(v) for v in a.levels.split(",")]):
            name = cond if cond == "clean" else f"{cond}-{level}"
            frames, th = render(cond, level, a.seed + 100 * level)
            T = 20
            clips = np.stack([frames[i:i + T] for i in range(FRAMES - T + 1)])[:, :, None]
            np.save(os.path.join(a.out, name + ".npy"), clips.astype(np.float32))
            np.save(os.path.join(a.out, name + "-theta.npy"), th)
            if a.mp4:
                p = subprocess.Popen(["ffmpeg", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "gray",
                                      "-s", f"{SIZE}x{SIZE}", "-r", str(FPS), "-i", "-", "-c:v", "libx264",
                                      "-qp", "0", "-pix_fmt", "yuv420p", os.path.join(a.out, name + ".mp4")],
                                     stdin=subprocess.PIPE)
                p.communicate((frames * 255).round().astype(np.uint8).tobytes())
            print(name, clips.shape)
    json.dump(dict(gamma0=G0, gamma1=G1, fps=FPS, dt=1 / FPS), open(os.path.join(a.out, "truth.json"), "w"))


if __name__ == "__main__":
    main()
