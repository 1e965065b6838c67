"""twoball from Python: two elastic-plastic balls colliding.

The analytical three-phase model of Li, Yang & Shi (Shock and Vibration 2019), the contact-law
integrator and the explicit finite-element verifier of the `twoball` command line, called in
the same process. Results are the command line's JSON objects as dicts (same keys, same bits);
FE histories are numpy arrays. All quantities are SI: m, s, kg, N, Pa, J.

Bad input raises ``ValueError`` with the command line's one-line message (naming the field, the
value and the allowed range). ``run`` and ``sweep`` release the GIL, report progress through an
optional callback ``progress(done, total)``, and stop within a fraction of a second on Ctrl-C
(``KeyboardInterrupt``).
"""

from __future__ import annotations

import json
import math
import numbers
import os
from typing import Any, Callable, Dict, Mapping, Optional, Union

import numpy as np

from . import _native
from . import laws

__all__ = ["analytic", "materials", "laws", "run", "sweep", "Run"]

Progress = Callable[[float, float], Any]


def _number(name: str, x: Any) -> str:
    """``x`` as a command-line number (exact: repr of a float round-trips)."""
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise ValueError(f"invalid {name} = {x!r}: allowed a number")
    return repr(float(x))


def _flags(options: Mapping[str, Any]) -> list:
    """Keyword arguments as command-line flags: ``v1=2.0`` -> ``--v1 2.0``; ``set={...}``
    -> ``--set KEY=VALUE`` each; ``wall="rigid"`` -> ``--wall rigid``."""
    args = []
    for key, value in options.items():
        if value is None:
            continue
        flag = "--" + key.replace("_", "-")
        if key == "set":
            for k, v in value.items():
                args += ["--set", f"{k}={_number(k, v)}"]
        elif key in ("param", "tparam"):
            for k, v in value.items():
                args += [flag, f"{k}={_number(k, v)}"]
        elif isinstance(value, str):
            args += [flag, value]
        elif isinstance(value, bool):
            if value:
                args.append(flag)
        elif isinstance(value, (os.PathLike,)):
            args += [flag, os.fspath(value)]
        else:
            args += [flag, _number("--" + key, value)]
    return args


def _cli(args: list) -> dict:
    return json.loads(_native.cli_json(args))


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
    curve: Optional[Union[str, os.PathLike]] = None,
    samples: int = 2001,
) -> dict:
    """The analytical three-phase collision of two balls (``twoball analytic --json``).

    material, material2: preset names (``twoball.materials()["presets"]``); diameter,
    diameter2: m; v1, v2: normal speeds before impact, m/s, positive towards ball 2 (v2
    default -1, or 0 with ``wall``); v1t, v2t: tangential speeds, m/s; mu: friction
    coefficient of the pair (default: mean of the materials'); wall: ``"rigid"`` or
    ``"elastic"`` half-space instead of ball 2; set: material overrides in SI units,
    ``{"yield": 2e8}`` for both balls or ``{"ball2.material.E": 2e11}``; curve: also write
    the contact history CSV there, ``samples`` rows.

    Returns the dict of ``twoball analytic --json`` (keys documented in the README, section
    "Analytical model": e [-], v1_after [m/s], delta_max [m], t3 [s], eta [-], ...).
    Raises ValueError on bad input.
    """
    opts = dict(
        material=material,
        diameter=diameter,
        v1=v1,
        v2=v2,
        material2=material2,
        diameter2=diameter2,
        v1t=v1t,
        v2t=v2t,
        mu=mu,
        wall=wall,
        set=set,
        curve=curve,
    )
    args = ["analytic"] + _flags(opts)
    if samples != 2001:
        args += ["--samples", str(int(samples))]
    return _cli(args + ["--json"])


def materials() -> dict:
    """Table 1 of the paper and the material presets (``twoball materials --json``).

    Keys: ``presets`` (name, E [Pa], nu [-], rho [kg/m^3], yield [Pa], tangent [Pa], mu [-],
    mu_static [-], zeta [-]), ``rows`` (zeta and eta against the printed values), the eta
    readings tried and the discrepancies of the paper.
    """
    return _cli(["materials", "--json"])


class Run:
    """The result of one scene (``twoball run``).

    results: dict with the keys of results.json (FE e [-], v1_after [m/s], delta_max [m],
    contact_duration [s], eta [-], energy_error [-], fe, analytic, relative_difference,
    warnings, scene, ...).

    history: dict of numpy float64 arrays, one per history.csv column, keyed by the column
    name without its unit: t [s] (time since first touch), delta [m] (approach of the mass
    centres), normal_force [N], tangential_force [N], v1x..v2z [m/s] (centre-of-mass
    velocities), w1x..w2z [rad/s] (angular velocities), kinetic, elastic, plastic,
    hourglass, contact_stored, contact_dissipated, total [J] (energies of the whole
    system), impulse [N s] (accumulated every step) and normal_force_smoothed [N] (a
    triangular window of half-width T_c/20 that keeps the impulse). ``units`` maps each name to its unit; ``columns`` keeps the csv order.
    """

    def __init__(self, results: dict, history: Dict[str, np.ndarray], units: Dict[str, str]):
        self.results = results
        self.history = history
        self.units = units
        self.columns = list(history)

    def __getitem__(self, key: str) -> Any:
        return self.results[key]

    def __repr__(self) -> str:
        e = self.results.get("e")
        return f"<twoball.Run e={e!r} rows={len(self.history.get('t', []))}>"


def _toml_value(path: str, value: Any) -> str:
    """An override value in the ``--set`` syntax (a TOML value)."""
    value = _plain(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        x = float(value)
        if not math.isfinite(x):
            return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")
        return repr(x)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(path, v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml_value(path, v)}" for k, v in value.items()) + " }"
    raise ValueError(f"--set {path}: value {value!r} is not a number, string, list or dict")


def _plain(x: Any) -> Any:
    """Numpy scalars and arrays as plain Python values (for JSON)."""
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, Mapping):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return x


def run(
    scene: Union[None, str, os.PathLike, Mapping[str, Any]] = None,
    *,
    out: Union[None, str, os.PathLike] = None,
    progress: Optional[Progress] = None,
    vtu_ascii: bool = False,
    overrides: Optional[Mapping[str, Any]] = None,
    tolerance: Optional[float] = None,
    max_refinements: int = 2,
    **more: Any,
) -> Run:
    """One scene, FE beside the analytical model (``twoball run``).

    scene: a scene TOML file, a dict with a scene's keys (``{"ball1": {"material":
    "copper-fe", "diameter": 0.02, "velocity": [1, 0, 0]}, ...}``), or None for the default
    scene (the paper's Figure 8 case). Overrides are dotted scene paths with values, as the
    command line's ``--set PATH=VALUE``: ``run(**{"ball1.velocity": [1, 0, 0]})``, or
    ``overrides={...}``. out: a folder for results.json and history.csv (and the scene's
    .vtu snapshots). progress: ``progress(done_s, total_s)`` with the simulated time so
    far and the expected end, s, called from the calling thread a few times a second.
    tolerance: refine until the relative error estimate of e is at most this fraction, as
    ``twoball run --tolerance`` (a head-on scene of identical balls or of a ball on a rigid
    wall runs the section's banded mesh family, about 4 s for the default scene at 0.005,
    unless the tolerance is 0.02 or looser and the scene's default levels meet it),
    with at most ``max_refinements`` levels beyond the first; the estimate is
    ``results["error_estimate"]``.

    Returns a :class:`Run` (results dict and history arrays). Raises ValueError on bad input,
    KeyboardInterrupt on Ctrl-C (the run stops within a few hundred steps; nothing written), RuntimeError when
    the run fails numerically.
    """
    sets = dict(overrides or {})
    sets.update(more)
    set_args = [f"{k}={_toml_value(k, v)}" for k, v in sets.items()]
    path = json_text = None
    if isinstance(scene, Mapping):
        json_text = json.dumps(_plain(scene), allow_nan=False)
    elif scene is not None:
        path = os.fspath(scene)
    text, names, columns = _native.run(
        path, json_text, set_args, None if out is None else os.fspath(out), vtu_ascii, progress,
        None if tolerance is None else float(tolerance), int(max_refinements),
    )
    history = {}
    units = {}
    for header, column in zip(names, columns):
        name, _, unit = header.partition(" [")
        history[name] = np.asarray(column, dtype=np.float64)
        units[name] = unit.rstrip("]")
    return Run(json.loads(text), history, units)


def sweep(
    path: Union[str, os.PathLike],
    out: Union[str, os.PathLike],
    *,
    jobs: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> dict:
    """A parameter sweep (``twoball sweep FILE --out DIR --jobs N``), resumable: cases already
    in ``out/cases/`` are kept, so calling it again after an interruption finishes the rest.

    jobs: worker threads (default: all cores). progress: ``progress(done, total)`` in cases.
    Returns a summary dict: total, ran, scaled (of those, FE results scaled from a similar
    case's run), skipped (already done), failed, in_csv, csv (the path of sweep.csv, units in
    its header). Raises ValueError on bad input,
    KeyboardInterrupt on Ctrl-C (finished cases kept).
    """
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int)):
        raise ValueError(f"invalid --jobs = {jobs!r}: allowed jobs >= 1")
    if jobs is not None and jobs < 0:
        raise ValueError(f"invalid --jobs = {jobs}: allowed jobs >= 1")
    return json.loads(_native.sweep(os.fspath(path), os.fspath(out), jobs, progress))

