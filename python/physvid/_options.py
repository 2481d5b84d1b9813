"""The options of ``estimate`` as Python keywords: ``options()`` lists them from the one
definition the command line parses, ``_flags`` turns keywords into its flags, and ``Request``
holds a source and its options for those who build an estimate step by step."""
from __future__ import annotations

import difflib
import json
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Optional

from . import _core


@dataclass(frozen=True)
class Option:
    """One of ``estimate``'s options as a keyword: its command-line flag, whether it takes a
    value (else ``True`` sets it) and may be given several times (a list then), its default as
    the command line prints it, and its help."""

    keyword: str
    flag: str
    takes_value: bool
    repeats: bool
    default: Optional[str]
    help: str


_OPTIONS: Optional[Dict[str, Option]] = None

# Keywords of earlier versions, still read.
_ALIASES = {"references": "reference"}


def options() -> Dict[str, Option]:
    """Every option of ``estimate`` that ``physvid.estimate`` takes as a keyword, by keyword:
    read from the one definition the command line parses, so the two cannot drift. Left out:
    the input (``source``), ``--out``/``--force`` (``out=``, ``Result.save``), ``--quiet``
    (``progress=False``) and a batch's ``--batch``/``--shard``/``--merge`` (a Python loop)."""
    global _OPTIONS
    if _OPTIONS is None:
        _OPTIONS = {o["keyword"]: Option(**o) for o in json.loads(_core.options())}
    return _OPTIONS


def _flags(given: Dict[str, Any]) -> List[str]:
    """The command line's flags for the keywords ``given`` (``None`` leaves an option at its
    default; ``True``/``False`` sets or leaves a switch; a list repeats an option that repeats,
    and is joined by commas for one that takes a list in one value)."""
    known = options()
    args: List[str] = []
    for key, value in given.items():
        key = _ALIASES.get(key, key)
        o = known.get(key)
        if o is None:
            close = difflib.get_close_matches(key, list(known), n=3)
            hint = f"; did you mean {', '.join(close)}?" if close else "; physvid.options() lists them"
            raise TypeError(f"estimate() got an unexpected keyword argument '{key}'{hint}")
        if value is None or value is False and not o.takes_value:
            continue
        if not o.takes_value:
            if value is not True:
                raise TypeError(f"{key}: a switch, True or False (got {value!r})")
            args.append(o.flag)
        elif isinstance(value, (list, tuple)):
            if o.repeats:
                for v in value:
                    args += [o.flag, str(v)]
            else:
                args += [o.flag, ",".join(str(v) for v in value)]
        else:
            args += [o.flag, str(value)]
    return args


class Request:
    """An estimate built step by step: a source and options, each checked by name when set
    (an unknown one is a ``TypeError`` naming the close ones)::

        req = physvid.Request("spring.mp4", start=2.5)
        req.model = "damped-oscillator"
        req.epochs = 100
        print(req.resolved()["training"]["epochs"])   # what estimate will run, defaults filled
        result = req.run(progress=False)              # physvid.estimate(req) is the same

    ``options`` holds the keywords set; ``resolved()`` is the typed request the command line's
    own parser makes of them (a value it refuses raises ``BadInputError`` there, before any
    training)."""

    def __init__(self, source: Any, **options: Any):
        object.__setattr__(self, "source", source)
        object.__setattr__(self, "options", {})
        for key, value in options.items():
            setattr(self, key, value)

    def __setattr__(self, key: str, value: Any) -> None:
        key = _ALIASES.get(key, key)
        _flags({key: None})  # the name checked now, the value by the parser
        self.options[key] = value

    def __getattr__(self, key: str) -> Any:
        key = _ALIASES.get(key, key)
        if key in self.__dict__.get("options", {}):
            return self.options[key]
        o = options().get(key)
        if o is None:
            raise AttributeError(key)
        return None  # not set: the option's default (``resolved()`` shows it)

    def resolved(self) -> Dict[str, Any]:
        """The typed request ``estimate`` will run, as a dict (every option at its value)."""
        from . import _source

        read, meta = _source(self.source)
        return json.loads(_core.request(read, _flags(self.options), meta=meta))

    def run(self, **kw: Any) -> Any:
        """``physvid.estimate(self, **kw)`` (``progress``, ``out``, or more options)."""
        from . import estimate

        return estimate(self, **kw)

    def __repr__(self) -> str:
        given = ", ".join(f"{k}={v!r}" for k, v in self.options.items())
        return f"Request({self.source!r}{', ' if given else ''}{given})"
