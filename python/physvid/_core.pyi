"""Type stubs of the compiled module (python/src/lib.rs)."""
from typing import Callable, List, Optional, Tuple, Union

import numpy as np

class PhysvidError(Exception): ...
class BadInputError(PhysvidError): ...
class NoEstimateError(PhysvidError): ...
class UnreliableError(PhysvidError): ...

class Fitted:
    def report(self) -> str: ...
    def save(self, out: str, force: bool = False) -> None: ...

def generate(args: List[str], out: str) -> str: ...
def estimate(
    source: Union[str, np.ndarray],
    model: Optional[str] = None,
    dt: Optional[float] = None,
    fps: Optional[float] = None,
    references: Optional[str] = None,
    epochs: Optional[int] = None,
    seed: int = 0,
    device: str = "auto",
    threads: Optional[int] = None,
    quiet: bool = False,
    out: Optional[str] = None,
    on_epoch: Optional[Callable[[int, int, float, List[Tuple[str, float]]], None]] = None,
) -> Fitted: ...
def track(
    video: str,
    start: Optional[float] = None,
    end: Optional[float] = None,
    fps: Optional[float] = None,
) -> Optional[str]: ...
