"""The wheel `maturin build` makes installs with pip into a fresh venv that already has torch
2.13 (as a cluster node's shared install would), imports, and estimates a small set there."""
import os
import subprocess
import sys
import venv
from pathlib import Path

import torch

ROOT = Path(__file__).resolve().parents[2]


def wheel(tmp: Path) -> Path:
    """scripts/test.sh's wheel (PHYSVID_WHEEL), else one built here."""
    given = os.environ.get("PHYSVID_WHEEL")
    if given:
        return Path(given)
    maturin = Path(sys.executable).with_name("maturin")
    subprocess.run([maturin, "build", "--quiet", "--release", "-m", ROOT / "python" / "Cargo.toml",
                    "--auditwheel", "skip", "-o", tmp], check=True, timeout=1200)
    return next(tmp.glob("physvid-*.whl"))


def test_the_wheel_installs_into_a_fresh_venv_with_torch_and_estimates(tmp_path):
    built = wheel(tmp_path / "wheels")
    fresh = tmp_path / "fresh"
    venv.create(fresh)
    python = fresh / "bin" / "python"
    # torch 2.13 and what it needs (pip too), already installed: this venv's packages but
    # physvid, shared through a .pth file as a node's module tree would be.
    ours = Path(torch.__file__).parents[1]
    shared = tmp_path / "shared"
    shared.mkdir()
    for entry in ours.iterdir():
        if not entry.name.startswith(("physvid", "_physvid")):
            (shared / entry.name).symlink_to(entry)
    site = next((fresh / "lib").glob("python3*/site-packages"))
    (site / "shared.pth").write_text(f"{shared}\n")
    # No index: the dependencies (numpy, torch==2.13.0) must be found installed.
    done = subprocess.run([python, "-m", "pip", "install", "--no-index", "--quiet",
                           "--disable-pip-version-check", built],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    script = (
        "import physvid\n"
        "print(physvid.__file__)\n"
        "d = physvid.generate('intensity', samples=40, size=16, seed=1)\n"
        "r = physvid.estimate(d, epochs=3, threads=1, progress=False)\n"
        "print(sorted(r.parameters))\n"
    )
    run = subprocess.run([python, "-c", script], capture_output=True, text=True, timeout=300,
                         cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    where, names = run.stdout.splitlines()[:2]
    assert where.startswith(str(site)), where
    assert names == "['gamma0', 'gamma1']", run.stdout
