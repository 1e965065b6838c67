"""Type stubs of twoball.laws (SI units)."""

import os
from typing import Any, Dict, Mapping, Optional, Union

def list() -> Dict[str, Any]:
    """The built-in normal and tangential contact laws with their parameters (key, unit,
    doc, default for two copper-fe balls of D = 0.02 m)."""

def run(
    law: str,
    params: Optional[Mapping[str, float]] = None,
    *,
    tangential: str = "coulomb",
    tparams: Optional[Mapping[str, float]] = None,
    tolerance: Optional[float] = None,
    curve: Union[None, str, os.PathLike] = None,
    **balls: Any,
) -> Dict[str, Any]:
    """One impact under a normal and a tangential law (``twoball laws run --json``); params
    in SI units; balls as for twoball.analytic. Raises ValueError on bad input."""
