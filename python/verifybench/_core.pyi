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
    scores: Optional[npt.ArrayLike] = None,
    prior_T: Optional[npt.ArrayLike] = None,
    prior_cov: Optional[npt.ArrayLike] = None,
    seed: int = 1,
    **settings: Any,
) -> Dict[str, Any]: ...
def settings() -> List[Dict[str, Any]]: ...
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
