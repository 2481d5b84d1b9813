"""physvid: physical parameters from video, without labels.

The Rust estimator and generator of this workspace, called in process (``physvid._core``,
built with maturin and PyO3). ``generate`` renders a seeded synthetic data set as ``gen`` does;
``estimate`` fits a known law to a data set, an array, a video or an image folder and grades
the answer, as ``estimate`` does; ``track`` follows the object of a video and fits each law
where it holds (the second route ``estimate`` prints as ``track:``)::

    import physvid
    data = physvid.generate("intensity", samples=200, size=32, seed=5)
    result = physvid.estimate(data, threads=2)
    print(result.parameters["gamma0"].value, result.verdict.grade)
"""
from __future__ import annotations

# libtorch comes from the torch wheel: torch is loaded first, so the module finds it.
import torch  # noqa: F401

import html
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Union

import numpy as np

from . import _core
from ._options import Option, Request, _flags, options
from ._core import BadInputError, NoEstimateError, PhysvidError, UnreliableError

__all__ = [
    "generate",
    "estimate",
    "track",
    "options",
    "Option",
    "Request",
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
    """A data set as ``gen`` makes it, held in memory: frames ``[N, T, C, H, W]`` float32,
    ``dt``, the truth and meta.json. Nothing is on disk until ``save`` writes it."""

    def __init__(self, frames: np.ndarray, meta: str, preview: bytes):
        self._meta_text = meta
        self.meta: Dict[str, Any] = json.loads(meta)
        self.dt: float = float(self.meta["dt"])
        self.truth: Dict[str, float] = dict(self.meta["model"]["parameters"])
        self.frames: np.ndarray = frames
        self._preview = preview

    def save(self, folder: Union[str, os.PathLike], force: bool = False) -> Path:
        """Writes the data set into ``folder`` exactly as ``gen --out FOLDER`` writes it
        (frames.npy, meta.json, preview.png; ``force``: into a folder this tool did not make)."""
        _core.save(self.frames, self._meta_text, self._preview, str(folder), force)
        return Path(folder)

    def __repr__(self) -> str:
        shape = "x".join(str(s) for s in self.meta["shape"])
        return f"Dataset({self.meta['scenario']}, {shape}, dt={self.dt})"

    def preview(self, clips: int = 4, frames: int = 8):
        """A matplotlib figure of the first ``frames`` frames (evenly spread over a clip) of the
        first ``clips`` clips, one row a clip, with their times: what preview.png shows
        (matplotlib must be installed)."""
        plt = _pyplot()
        x = self.frames
        n, t = min(clips, x.shape[0]), min(frames, x.shape[1])
        steps = np.linspace(0, x.shape[1] - 1, t).round().astype(int)
        fig, axes = plt.subplots(n, t, figsize=(1.4 * t, 1.4 * n), squeeze=False)
        for i in range(n):
            for j, k in enumerate(steps):
                image = x[i, k].transpose(1, 2, 0)
                ax = axes[i][j]
                ax.imshow(image[..., 0] if image.shape[2] == 1 else image, cmap="gray", vmin=0, vmax=1)
                ax.set_xticks([])
                ax.set_yticks([])
                if i == 0:
                    ax.set_title(f"{k * self.dt:.3g} s", fontsize=8)
        fig.suptitle(repr(self), fontsize=9)
        return fig


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
    ``gen`` with the same options once saved; rendered in memory, nothing written.
    ``perturb`` and ``set`` take ``gen``'s text
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
    return Dataset(*_core.generate(args))


@dataclass(frozen=True)
class Parameter:
    """One answer: its value, standard error (None where unknown), unit, ``SI`` or ``latent``,
    and the truth with the relative error where the data set gives them; where the track
    measured the value too, ``routes`` holds each route's (``latent``, ``latent_error``: None
    where it has none, ``track``, ``track_error``) and ``agree``: the value is the track's, the
    latent's its second opinion; ``unlike``, where present, names the rate on which the routes
    disagree, so the latent's value here is no second opinion though its own two agree."""

    name: str
    value: float
    standard_error: Optional[float]
    unit: str
    units: str
    truth: Optional[float] = None
    relative_error: Optional[float] = None
    routes: Optional[Dict[str, Any]] = None


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
                routes=p.get("routes"),
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

    @property
    def track(self):
        """The object's own track on a video (``track``'s table: a pandas DataFrame where pandas
        is installed, else a dict of numpy arrays), or None (a data set, an array, a folder of
        images, or nothing followed)."""
        route = self.report.get("track")
        return None if route is None else _track_table(route)

    def __repr__(self) -> str:
        values = ", ".join(f"{p.name}={p.value:.6g}" for p in self.parameters.values())
        return f"Result({self.model}: {values}; {self.verdict.grade})"

    def plot(self):
        """A matplotlib figure (matplotlib must be installed): each of the physics block's
        parameters over the epochs with its final value and truth (parameters.png), and on a
        video the object's track along its axis with each law's span shaded (track.png)."""
        plt = _pyplot()
        # The physics block's own parameters are those trained (a derived one, as the incline's
        # μ from its acceleration, has no history).
        names = list(self.report.get("block_parameters") or self.parameters)
        route = self.report.get("track")
        rows = len(names) + (1 if route else 0)
        fig, axes = plt.subplots(rows, 1, figsize=(7, 2.2 * rows), squeeze=False)
        epochs = [h["epoch"] for h in self.history]
        for i, name in enumerate(names):
            ax, p = axes[i][0], self.parameters.get(name)
            ax.plot(epochs, [h["parameters"][i] for h in self.history], label=name)
            if p is not None:
                ax.axhline(p.value, color="C1", lw=0.8, label=f"estimate {p.value:.6g}")
                if p.truth is not None:
                    ax.axhline(p.truth, color="C2", ls="--", lw=0.8, label=f"truth {p.truth:.6g}")
            ax.set_ylabel(name if p is None else f"{name} ({p.unit})")
            ax.legend(fontsize=7)
        axes[len(names) - 1][0].set_xlabel("epoch")
        if route:
            ax, t = axes[-1][0], route["track"]
            ax.plot(t["t"], t["along"], ".", ms=2, color="k", label="the track")
            for k, law in enumerate(route["laws"]):
                chosen = law["law"] == route.get("chosen")
                ax.axvspan(law["first_s"], law["last_s"], alpha=0.25 if chosen else 0.08,
                           color=f"C{k}", label=f"{law['law']}{' (chosen)' if chosen else ''}")
            ax.set_xlabel("time (s)")
            ax.set_ylabel("along its axis (px)")
            ax.legend(fontsize=7)
        fig.suptitle(f"{self.model}: verdict {self.verdict.grade}", fontsize=9)
        fig.tight_layout()
        return fig

    def _repr_html_(self) -> str:
        """A notebook's view: the model, the verdict with its reasons, the values with their
        errors and truth, the model choice and the track's line."""
        e = html.escape

        def num(v: Optional[float]) -> str:
            return "–" if v is None else f"{v:.6g}"

        rows = "".join(
            f"<tr><td>{e(p.name)}</td><td>{num(p.value)}</td><td>{num(p.standard_error)}</td>"
            f"<td>{e(p.unit)}</td><td>{num(p.truth)}</td>"
            f"<td>{'–' if p.relative_error is None else f'{100 * p.relative_error:+.2f} %'}</td></tr>"
            for p in self.parameters.values()
        )
        reasons = "".join(
            f"<li><b>{e(r.check)}</b> [{e(r.grade)}]: {e(r.detail)}</li>" for r in self.verdict.reasons
        )
        choice = ""
        if self.report.get("model_choice"):
            mc = self.report["model_choice"]
            choice = "<p>model choice: " + ", ".join(
                e(f"{c.get('model')} ({'chosen, ' if c.get('model') == mc.get('chosen') else ''}"
                  f"{c.get('grade', '?')})")
                for c in mc.get("candidates", [])
            ) + "</p>"
        line = _track_line(self.report["track"]) if self.report.get("track") else ""
        return (
            f"<div class='physvid-result'><p><b>{e(self.model)}</b> — verdict "
            f"<b>{e(self.verdict.grade)}</b></p>"
            + (f"<ul>{reasons}</ul>" if reasons else "")
            + "<table><tr><th>parameter</th><th>estimate</th><th>± std. err.</th><th>unit</th>"
            "<th>truth</th><th>rel. error</th></tr>"
            + rows
            + "</table>"
            + choice
            + (f"<p>{e(line)}</p>" if line else "")
            + "</div>"
        )


Source = Union[str, os.PathLike, Dataset, np.ndarray, "torch.Tensor"]


def _source(source: Source):
    """What the module reads for ``source``: a path, or float32 clips in memory (with their
    meta.json for a ``Dataset``)."""
    if isinstance(source, Dataset):
        return source.frames, source._meta_text  # in memory, with its meta.json
    if isinstance(source, (str, os.PathLike)):
        return str(Path(source)), None
    # Read in memory (a CPU tensor's numpy view costs no copy; the module copies once).
    array = source.detach().cpu().numpy() if isinstance(source, torch.Tensor) else source
    return np.ascontiguousarray(array, dtype=np.float32), None


def estimate(
    source: Union[Source, Request],
    *,
    progress: Union[bool, Callable[[Epoch], None]] = True,
    out: Union[str, os.PathLike, None] = None,
    **options: Any,
) -> Result:
    """Estimates on ``source``: a path (data set folder, ``.npy``, video, image folder), a
    ``Dataset``, a ``Request`` (its source and options, then these), or an array / tensor ``[N, T, C, H, W]`` (read in memory, as a bare ``.npy``
    would be: ``dt`` is needed). Every option of ``estimate`` is a keyword of the same name and
    default (``physvid.options()`` lists them with their help): ``model`` (a built-in's name or
    a model file; ``None``: the one a data set's meta.json names, else chosen by the evidence;
    ``"auto"``: chosen always), ``dt``, ``fps``, ``reference`` (``--reference``'s text),
    ``epochs``, ``seed``, ``threads``, ``start``, ``end``, ``crop``, ``incline_deg``,
    ``candidate`` (a list of model files), ``ensemble``, ``encoder``, ...; the command line's own
    parser reads them, so a value it refuses is a ``BadInputError`` with its message, and an
    unknown keyword a ``TypeError`` naming the close ones. ``progress``: ``True`` shows a tqdm bar
    (``tqdm.auto``: a widget in notebooks) where tqdm is installed, else the command line's
    lines; ``False`` nothing; a function is called with each ``Epoch``. With ``out``, writes what
    ``estimate --out`` writes. Raises ``BadInputError``, ``NoEstimateError`` or
    ``UnreliableError`` (its ``result`` the graded estimate) as ``estimate`` exits 2, 3 or 4."""
    if isinstance(source, Request):
        source, options = source.source, {**source.options, **options}
    args = _flags(options)
    read, meta = _source(source)
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
            args,
            quiet=not progress,
            out=None if out is None else str(out),
            on_epoch=on_epoch,
            meta=meta,
        )
    except UnreliableError as e:
        e.result = Result(e.args[2])
        raise
    finally:
        if bar is not None:
            bar.close()
    return Result(fitted)


def _pyplot():
    """matplotlib's pyplot, or an ImportError that says how to get it."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError("the figures need matplotlib: pip install matplotlib") from e
    return plt


_TRACK_COLUMNS = ("t", "file_s", "x", "y", "quality", "along")


def _track_table(route: Dict[str, Any]):
    """report.json's ``track`` as a table: t (s of real time), file_s (the file's own time), x and
    y (pixels of the displayed frame), quality, along (the position along the motion's own axis,
    pixels; for a ``brightness`` reading, the grey level of the region whose light changes); the
    laws fitted, the law chosen, the axis, the noise and how the positions were read
    (``reading``: centroids, whole, rod, matches or brightness) and ``steadied`` (the largest shift
    taken off where the frames were steadied against a camera's shake, else None) in ``attrs`` (a
    DataFrame) or under those keys (a dict)."""
    t = route["track"]
    columns = {c: np.asarray(t[c], dtype=np.float64) for c in _TRACK_COLUMNS}
    about = {
        "laws": route.get("laws", []),
        "chosen": route.get("chosen"),
        "axis": t["axis"],
        "noise": t["noise"],
        "reading": t.get("reading"),
        "steadied": t.get("steadied"),
    }
    try:
        import pandas as pd
    except ImportError:
        return {**columns, **about}
    frame = pd.DataFrame(columns)
    frame.attrs.update(about)
    return frame


def _track_line(route: Dict[str, Any]) -> str:
    """The track's line as ``estimate`` prints it (its chosen law, span and values)."""
    law = next((l for l in route.get("laws", []) if l["law"] == route.get("chosen")), None)
    if law is None:
        return "track: no law explains it within its noise"
    values = ", ".join(f"{v['name']} {v['value']:.6g} ± {v['error']:.2g} {v['unit']}" for v in law["values"])
    return f"track: {law['law']} over {law['first_s']:.2f}–{law['last_s']:.2f} s: {values}"


def track(
    video: Union[str, os.PathLike],
    start: Optional[float] = None,
    end: Optional[float] = None,
    fps: Optional[float] = None,
):
    """The object's own track in ``video`` (``start``/``end``: seconds of its own timeline, as
    ``estimate --start``; ``fps``: frames a second of real time, as ``--fps``), in seconds and
    without training: a pandas DataFrame (t, file_s, x, y, quality, along) where pandas is
    installed, else a dict of numpy arrays; the laws fitted where they hold (a damped
    oscillation, a constant acceleration, a swing; where nothing that moves follows a law, a
    brightness's exponential decay), the one chosen, the axis, the noise and how the positions
    were read (``reading``: a rod's read by its axes; ``brightness``: not a position) in ``attrs`` (or under those
    keys). None where nothing lives long enough to follow. Raises
    ``BadInputError`` for a file that is no video."""
    found = _core.track(str(Path(video)), start=start, end=end, fps=fps)
    return None if found is None else _track_table(json.loads(found))
