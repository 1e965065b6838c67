"""Contact laws (``twoball laws``): list them, and run one impact under a chosen normal and
tangential law (``twoball laws run --json``). SI units throughout."""

from __future__ import annotations

import builtins
import json
import os
from typing import Any, Mapping, Optional, Union

from . import _native

__all__ = ["list", "run"]


def list() -> dict:  # noqa: A001 (the name of the command)
    """The built-in contact laws: ``{"normal": [...], "tangential": [...]}``, each law with
    name, title, source, dem_codes and params (key, unit, doc, default for two copper-fe
    balls of D = 0.02 m)."""
    return json.loads(_native.cli_json(["laws"]))


def run(
    law: str,
    params: Optional[Mapping[str, float]] = None,
    *,
    tangential: str = "coulomb",
    tparams: Optional[Mapping[str, float]] = None,
    tolerance: Optional[float] = None,
    curve: Union[None, str, os.PathLike] = None,
    **balls: Any,
) -> dict:
    """One impact under normal law ``law`` with ``params`` (KEY: value in SI units, as
    ``--param``) and tangential law ``tangential`` with ``tparams`` (``--tparam``), integrated
    with relative step tolerance ``tolerance`` (default as the CLI's).

    balls: the keyword arguments of :func:`twoball.analytic` (material, diameter [m], v1, v2,
    v1t, v2t [m/s], material2, diameter2, mu, wall, set). curve: write every integrator step
    (t [s], delta [m], delta_dot [m/s], force [N], tangential force [N], slip speed [m/s]).

    Returns the dict of ``twoball laws run --json``. Raises ValueError on bad input.
    """
    from . import _flags

    unknown = builtins.set(balls) - {
        "material", "diameter", "v1", "v2", "material2", "diameter2", "v1t", "v2t", "mu",
        "wall", "set",
    }
    if unknown:
        raise ValueError(f"unknown ball option(s) {sorted(unknown)}: see twoball.analytic")
    opts = dict(balls)
    opts.update(param=params or {}, tangential=tangential, tparam=tparams or {})
    opts.update(tolerance=tolerance, curve=curve)
    return json.loads(_native.cli_json(["laws", "run", "--law", law] + _flags(opts) + ["--json"]))
