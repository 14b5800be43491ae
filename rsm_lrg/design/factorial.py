"""Full factorial designs with equally spaced levels (3^k for response surfaces).

Levels are equally spaced in coded units from -1 to +1 (3 levels: -1, 0, +1); the runs come
from pyDOE3's ``fullfact`` (first factor changing fastest, the standard order).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ParameterError
from .core import Design, as_factor_space, check_center, cross_categoric, numeric_part

__all__ = ["full_factorial"]

#: Largest design generated (a guard against typing 10 factors at 5 levels by mistake).
MAX_RUNS = 100_000


def full_factorial(
    factors: Any,
    levels: int = 2,
    center: int = 0,
    seed: Any = None,
    randomize: bool = True,
) -> Design:
    """Full factorial design, every factor at ``levels`` equally spaced levels.

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        As for :func:`~rsm_lrg.design.box_behnken` (1 or more factors).
    levels : int, default 2
        Levels per factor (≥ 2); coded -1 ... +1 equally spaced (two, as Design-Expert and JMP).
    center : int, default 0
        Extra centre runs added after the factorial runs (with an odd number of levels the
        factorial already holds one).
    seed, randomize
        As for :func:`~rsm_lrg.design.box_behnken`.

    Returns
    -------
    Design
        The runs in coded and actual units, in run order (:meth:`~rsm_lrg.design.Design.to_frame`
        gives the design CSV layout).

    Examples
    --------
    >>> d = full_factorial({"x": (0, 2), "y": (10, 20)}, levels=3, randomize=False)
    >>> d.n_runs, d.actual["x"].tolist()[:3]
    (9, [0.0, 1.0, 2.0])
    """
    space = as_factor_space(factors)
    k = numeric_part(space)[1]
    if k < 1:
        raise ValueError("a factorial design needs at least one numeric factor")
    if isinstance(levels, (bool, np.bool_)) or int(levels) != levels or levels < 2:
        raise ParameterError("levels", f"levels must be a whole number of at least 2 (got {levels!r})")
    levels = int(levels)
    center = check_center(center)
    if levels ** k + center > MAX_RUNS:
        raise ValueError(f"{levels}^{k} = {levels ** k} runs is more than this generator makes ({MAX_RUNS})")
    from pyDOE3 import fullfact

    idx = np.asarray(fullfact([levels] * k), dtype=float)
    coded = 2.0 * idx / (levels - 1) - 1.0
    coded = np.vstack([coded, np.zeros((center, k))])
    options = {"levels": levels, "center": center}
    coded, _ = cross_categoric(space, coded)
    return Design.from_standard(space, "full-factorial", coded, seed=seed, randomize=randomize,
                                options=options)
