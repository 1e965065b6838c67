"""The compiled half of twoball (called by the Python half; not a public interface)."""

from typing import Any, Callable, List, Optional, Tuple

def cli_json(args: List[str]) -> str:
    """JSON text of ``twoball ARGS --json`` (analytic, materials, laws, laws run)."""

def run(
    scene_path: Optional[str],
    scene_json: Optional[str],
    sets: List[str],
    out: Optional[str],
    vtu_ascii: bool,
    progress: Optional[Callable[[float, float], Any]],
    tolerance: Optional[float],
    max_refinements: int,
) -> Tuple[str, List[str], List[List[float]]]:
    """results.json text, history.csv column headers (with units) and the columns."""

def sweep(
    path: str,
    out: str,
    jobs: Optional[int],
    progress: Optional[Callable[[float, float], Any]],
) -> str:
    """The sweep's summary as JSON text."""
