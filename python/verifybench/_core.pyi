# Type stubs of the compiled module (python/verifybench/_core.cpp).
from typing import Any, Dict, List, Optional

import numpy as np
import numpy.typing as npt

__version__: str
git_commit: str

class InputError(ValueError): ...

def solvers() -> List[str]: ...
def generators() -> List[str]: ...
def solve(
    solver: str,
    src: npt.ArrayLike,
    dst: npt.ArrayLike,
    *,
    eps: float = 0.1,
    inlier_threshold: Optional[float] = None,
    min_inliers: int = 0,
    time_limit: float = 60.0,
    seed: int = 1,
    threads: int = 1,
    accept: str = "count",
    alpha: float = 0.001,
    null_draws: int = 20,
    max_null_draws: int = 100,
    prior_gate: float = 0.999,
    scores: Optional[npt.ArrayLike] = None,
    prior_T: Optional[npt.ArrayLike] = None,
    prior_cov: Optional[npt.ArrayLike] = None,
) -> Dict[str, Any]: ...
def synthetic(
    *,
    n: int = 500,
    outliers: float = 0.5,
    noise: float = 0.01,
    dim: int = 3,
    seed: int = 1,
    kind: str = "uniform",
    extent: float = 10.0,
    negative: bool = False,
) -> Dict[str, Any]: ...
def read_dump(path: str) -> Dict[str, Any]: ...
