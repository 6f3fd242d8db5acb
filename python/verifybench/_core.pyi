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
    source_cloud: Optional[npt.ArrayLike] = None,
    target_cloud: Optional[npt.ArrayLike] = None,
    seed: int = 1,
    **settings: Any,
) -> Dict[str, Any]: ...
def settings() -> List[Dict[str, Any]]: ...
def generator_settings() -> List[Dict[str, Any]]: ...
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
    group_ratio: float = 0.5,
    grid_spacing: float = 2.0,
    overlap: float = 0.3,
    tail_dof: float = 3.0,
    anisotropy: float = 5.0,
    near_radius: float = 1.0,
    cell: float = 0.5,
    score_separation: float = 1.0,
    planar_motion: bool = False,
    prior_rot_deg: float = 0.0,
    prior_trans: float = 0.0,
) -> Dict[str, Any]: ...
def read_dump(path: str) -> Dict[str, Any]: ...
