"""physvid: physical parameters from video, without labels.

The Rust estimator and generator of this workspace, called in process (``physvid._core``,
built with maturin and PyO3). ``generate`` renders a seeded synthetic data set as ``gen`` does;
``estimate`` fits a known law to a data set, an array, a video or an image folder and grades
the answer, as ``estimate`` does::

    import physvid
    data = physvid.generate("intensity", samples=200, size=32, seed=5)
    result = physvid.estimate(data, threads=2)
    print(result.parameters["gamma0"].value, result.verdict.grade)
"""
from __future__ import annotations

# libtorch comes from the torch wheel: torch is loaded first, so the module finds it.
import torch  # noqa: F401

import json
import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Union

import numpy as np

from . import _core
from ._core import BadInputError, NoEstimateError, PhysvidError, UnreliableError

__all__ = [
    "generate",
    "estimate",
    "Dataset",
    "Result",
    "Parameter",
    "Verdict",
    "Epoch",
    "PhysvidError",
    "BadInputError",
    "NoEstimateError",
    "UnreliableError",
]


class Dataset:
    """A data set as ``gen`` writes it: frames ``[N, T, C, H, W]`` float32, ``dt``, the truth
    and meta.json. It lives in a temporary folder until the object goes; ``save`` copies it."""

    def __init__(self, folder: Path, keep: Optional[tempfile.TemporaryDirectory] = None):
        self.path = Path(folder)
        self._keep = keep
        self.meta: Dict[str, Any] = json.loads((self.path / "meta.json").read_text())
        self.dt: float = float(self.meta["dt"])
        self.truth: Dict[str, float] = dict(self.meta["model"]["parameters"])
        self._frames: Optional[np.ndarray] = None

    @property
    def frames(self) -> np.ndarray:
        """The clips, ``[N, T, C, H, W]`` float32 (read from frames.npy when first asked)."""
        if self._frames is None:
            self._frames = np.load(self.path / "frames.npy")
        return self._frames

    def save(self, folder: Union[str, os.PathLike]) -> Path:
        """Writes the data set into ``folder`` (created; it must not exist), exactly as ``gen``
        writes it."""
        folder = Path(folder)
        if folder.exists():
            raise BadInputError(f"{folder}: exists already; save into a new folder")
        shutil.copytree(self.path, folder)
        return folder

    def __repr__(self) -> str:
        shape = "x".join(str(s) for s in self.meta["shape"])
        return f"Dataset({self.meta['scenario']}, {shape}, dt={self.dt})"


def generate(
    scenario: str,
    setting: Optional[int] = None,
    seed: int = 0,
    samples: Optional[int] = None,
    size: Optional[int] = None,
    frames: Optional[int] = None,
    dt: Optional[float] = None,
    noise: Optional[float] = None,
    perturb: Optional[str] = None,
    set: Optional[str] = None,
) -> Dataset:
    """A seeded synthetic data set of ``scenario`` (``gen --scenario``), the same bytes as
    ``gen`` with the same options. ``perturb`` and ``set`` take ``gen``'s text
    (``"shake:3,noise:2"``, ``"omega=2,zeta=0.1"``)."""
    args = ["--scenario", scenario, "--seed", str(seed)]
    for flag, value in [
        ("--setting", setting),
        ("--samples", samples),
        ("--size", size),
        ("--frames", frames),
        ("--dt", dt),
        ("--noise", noise),
        ("--perturb", perturb),
        ("--set", set),
    ]:
        if value is not None:
            args += [flag, str(value)]
    keep = tempfile.TemporaryDirectory(prefix="physvid-")
    folder = Path(keep.name) / scenario
    _core.generate(args, str(folder))
    return Dataset(folder, keep)


@dataclass(frozen=True)
class Parameter:
    """One answer: its value, standard error (None where unknown), unit, ``SI`` or ``latent``,
    and the truth with the relative error where the data set gives them."""

    name: str
    value: float
    standard_error: Optional[float]
    unit: str
    units: str
    truth: Optional[float] = None
    relative_error: Optional[float] = None


@dataclass(frozen=True)
class Epoch:
    """One epoch of the training kept, as ``progress`` sees it."""

    epoch: int
    most: int
    validation_error: float
    parameters: Dict[str, float]


@dataclass(frozen=True)
class Reason:
    check: str
    grade: str
    detail: str


@dataclass(frozen=True)
class Verdict:
    """``ok``, ``doubtful`` or ``unreliable``, with the reasons."""

    grade: str
    reasons: List[Reason] = field(default_factory=list)


class Result:
    """An estimate: its parameters, verdict, model, training history and the whole report
    (report.json as a dict); ``save`` writes what ``estimate --out`` writes."""

    def __init__(self, fitted: "_core.Fitted"):
        self._fitted = fitted
        report: Dict[str, Any] = json.loads(fitted.report())
        self.report = report
        self.model: str = report["model"]
        self.parameters: Dict[str, Parameter] = {
            p["name"]: Parameter(
                name=p["name"],
                value=p["estimate"],
                standard_error=p.get("standard_error"),
                unit=p["unit"],
                units=p["units"],
                truth=p.get("truth"),
                relative_error=p.get("relative_error"),
            )
            for p in report["parameters"]
        }
        v = report["verdict"]
        self.verdict = Verdict(
            v["grade"], [Reason(r["check"], r["grade"], r["detail"]) for r in v["reasons"]]
        )
        self.history: List[Dict[str, Any]] = report["history"]

    def save(self, folder: Union[str, os.PathLike], force: bool = False) -> Path:
        """Writes report.json, report.html, metrics.csv and the plots into ``folder``, as
        ``estimate --out FOLDER`` does (a folder this tool did not make is refused unless it is
        empty or ``force``)."""
        self._fitted.save(str(folder), force)
        return Path(folder)

    def to_pandas(self):
        """The parameters as a pandas DataFrame (pandas must be installed)."""
        import pandas as pd

        return pd.DataFrame([p.__dict__ for p in self.parameters.values()])

    def __repr__(self) -> str:
        values = ", ".join(f"{p.name}={p.value:.6g}" for p in self.parameters.values())
        return f"Result({self.model}: {values}; {self.verdict.grade})"


Source = Union[str, os.PathLike, Dataset, np.ndarray, "torch.Tensor"]


def estimate(
    source: Source,
    model: Optional[str] = None,
    dt: Optional[float] = None,
    fps: Optional[float] = None,
    references: Optional[str] = None,
    epochs: Optional[int] = None,
    seed: int = 0,
    device: str = "auto",
    threads: Optional[int] = None,
    progress: Union[bool, Callable[[Epoch], None]] = True,
    out: Union[str, os.PathLike, None] = None,
) -> Result:
    """Estimates the parameters of ``model`` (a built-in's name or a model file; ``None``: the
    one a data set's meta.json names, else chosen by the evidence; ``"auto"``: chosen always)
    from ``source``: a path (data set
    folder, ``.npy``, video, image folder), a ``Dataset``, or an array / tensor
    ``[N, T, C, H, W]`` (read in memory, as a bare ``.npy`` would be: ``dt`` is needed).
    ``references`` is ``estimate --reference``'s text. ``progress``: ``True`` shows a tqdm bar
    (``tqdm.auto``: a widget in notebooks) where tqdm is installed, else the command line's
    lines; ``False`` nothing; a function is called with each ``Epoch``. With ``out``, writes what
    ``estimate --out`` writes. Raises ``BadInputError``, ``NoEstimateError`` or
    ``UnreliableError`` (its ``result`` the graded estimate) as ``estimate`` exits 2, 3 or 4."""
    if isinstance(source, Dataset):
        read: Any = str(source.path)
    elif isinstance(source, (str, os.PathLike)):
        read = str(Path(source))
    else:
        # Read in memory (a CPU tensor's numpy view costs no copy; the module copies once).
        array = source.detach().cpu().numpy() if isinstance(source, torch.Tensor) else source
        read = np.ascontiguousarray(array, dtype=np.float32)
    on_epoch, bar = None, None
    if callable(progress):
        on_epoch = lambda e, most, err, values: progress(Epoch(e, most, err, dict(values)))  # noqa: E731
    elif progress:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            tqdm = None
        if tqdm is not None:
            bar = tqdm(unit="epoch", desc="physvid")

            def on_epoch(e, most, err, values):
                bar.total = most  # the run's --epochs, its default included
                bar.update(e - bar.n)
                bar.set_postfix_str(f"val {err:.2e} " + " ".join(f"{k} {v:.5g}" for k, v in values))

    try:
        fitted = _core.estimate(
            read,
            model=model,
            dt=dt,
            fps=fps,
            references=references,
            epochs=epochs,
            seed=seed,
            device=device,
            threads=threads,
            quiet=not progress,
            out=None if out is None else str(out),
            on_epoch=on_epoch,
        )
    except UnreliableError as e:
        e.result = Result(e.args[2])
        raise
    finally:
        if bar is not None:
            bar.close()
    return Result(fitted)
