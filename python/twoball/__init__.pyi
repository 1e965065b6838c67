"""Type stubs of the twoball Python package (SI units: m, s, kg, N, Pa, J)."""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Union

import numpy as np
import numpy.typing as npt

from . import laws as laws

Progress = Callable[[float, float], Any]
PathLike = Union[str, os.PathLike]

def analytic(
    material: str = "copper-fe",
    diameter: float = 0.02,
    v1: float = 1.0,
    v2: Optional[float] = None,
    *,
    material2: Optional[str] = None,
    diameter2: Optional[float] = None,
    v1t: float = 0.0,
    v2t: float = 0.0,
    mu: Optional[float] = None,
    wall: Optional[str] = None,
    set: Optional[Mapping[str, float]] = None,
    curve: Optional[PathLike] = None,
    samples: int = 2001,
) -> Dict[str, Any]:
    """Analytical three-phase collision (``twoball analytic --json``): diameters in m, speeds
    in m/s, overrides in SI; returns the CLI's JSON object (e [-], delta_max [m], t3 [s],
    eta [-], ...). Raises ValueError on bad input."""

def materials() -> Dict[str, Any]:
    """Table 1 and the material presets (``twoball materials --json``): E, yield, tangent in
    Pa, rho in kg/m^3, nu, mu, zeta dimensionless."""

class Run:
    """One scene's results: ``results`` (results.json's keys) and ``history`` (numpy arrays
    per history.csv column: t [s], delta [m], normal_force [N], tangential_force [N],
    v1x..v2z [m/s], w1x..w2z [rad/s], kinetic..total [J], impulse [N s],
    normal_force_smoothed [N])."""

    results: Dict[str, Any]
    history: Dict[str, npt.NDArray[np.float64]]
    units: Dict[str, str]
    columns: List[str]
    def __init__(
        self,
        results: Dict[str, Any],
        history: Dict[str, npt.NDArray[np.float64]],
        units: Dict[str, str],
    ) -> None: ...
    def __getitem__(self, key: str) -> Any: ...

def run(
    scene: Union[None, PathLike, Mapping[str, Any]] = None,
    *,
    out: Optional[PathLike] = None,
    progress: Optional[Progress] = None,
    vtu_ascii: bool = False,
    overrides: Optional[Mapping[str, Any]] = None,
    tolerance: Optional[float] = None,
    max_refinements: int = 2,
    **more: Any,
) -> Run:
    """One scene, FE beside the analytical model (``twoball run``); overrides are dotted
    scene paths (``--set`` syntax); progress(done_s, total_s) in simulated seconds;
    tolerance: refine until the relative error estimate of e is at most this fraction
    (``--tolerance``). Raises ValueError on bad input, KeyboardInterrupt on Ctrl-C."""

def sweep(
    path: PathLike,
    out: PathLike,
    *,
    jobs: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> Dict[str, Any]:
    """A resumable parameter sweep (``twoball sweep``); progress(done, total) in cases;
    returns total, ran, skipped, failed, in_csv and csv (the path of sweep.csv)."""
