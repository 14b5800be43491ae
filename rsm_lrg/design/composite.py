"""Central composite designs (Box & Wilson 1951): a 2^k cube, 2k star points, centre runs.

The star distance α follows the NIST/SEMATECH e-Handbook (section 5.3.3.6.1, "Central
Composite Designs") and Myers, Montgomery & Anderson-Cook, *Response Surface Methodology*
(3rd ed., 2009, section 7.4):

``"rotatable"``
    α = F^(1/4) with F = 2^k cube runs (full factorial cube): 1.414, 1.682, 2.000, 2.378
    for k = 2, 3, 4, 5.
``"practical"``
    α = k^(1/4) (Design-Expert's "practical" α, between face-centred and rotatable for
    k ≥ 6; for small k it is close to 1).
``"orthogonal"``
    Unblocked: the α that makes the quadratic columns uncorrelated (an orthogonal design),
    α = (Q F / 4)^(1/4) with Q = (√(F + T) − √F)², T = 2k + n0 (n0 all centre runs)
    [Myers, Montgomery & Anderson-Cook, Eq. 7.13]; e.g. k = 2, n0 = 1 gives α = 1 (the
    3² factorial) and k = 3, n0 = 1 gives α = 1.2154.
    Blocked into cube and star blocks: the α that blocks orthogonally,
    α = √( F (2k + n_s0) / (2 (F + n_c0)) ) [Box & Hunter 1957; Montgomery, *Design and
    Analysis of Experiments*, section 11.4.3] — this is the formula pyDOE3's ``ccdesign``
    uses for ``alpha="orthogonal"`` whether or not the design is blocked.
``"face"``
    α = 1 (face-centred, the same as ``face="faced"``).
float
    That α.

``face="inscribed"`` divides every coded setting by α, so the star points sit at ±1 (the
given low/high levels) and the cube at ±1/α; ``face="faced"`` puts the star points at ±1.
pyDOE3's ``ccdesign`` gives the same runs (as a multiset) for ``"rotatable"`` in every
face type and for ``"orthogonal"`` when blocked; see the tests.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import ParameterError
from .core import Design, as_factor_space, check_center, cross_categoric, numeric_part

__all__ = ["central_composite", "ccd_alpha"]

_FACES = {
    "circumscribed": "circumscribed", "ccc": "circumscribed",
    "inscribed": "inscribed", "cci": "inscribed",
    "faced": "faced", "face": "faced", "ccf": "faced",
}
_MAX_K = 10


def ccd_alpha(k: int, alpha: Any = "rotatable", center: tuple[int, int] = (0, 0), blocked: bool = False) -> float:
    """Star distance α [coded units] of a k-factor CCD with a full 2^k cube.

    Parameters
    ----------
    k : int
        Number of factors.
    alpha : {"rotatable", "orthogonal", "practical", "face"} or float
    center : (int, int)
        Centre runs with the cube and with the star points (used by ``"orthogonal"``).
    blocked : bool
        Whether cube and star form two blocks (changes the ``"orthogonal"`` rule).

    Returns
    -------
    float
        α [coded units].

    Notes
    -----
    >>> round(ccd_alpha(3), 3), round(ccd_alpha(4), 3)
    (1.682, 2.0)
    """
    F = 2 ** k
    if isinstance(alpha, str):
        word = alpha.strip().lower()
        if word in ("rotatable", "r"):
            return F ** 0.25
        if word in ("practical", "p"):
            return k ** 0.25
        if word in ("face", "faced", "f"):
            return 1.0
        if word in ("orthogonal", "o"):
            nc0, ns0 = center
            if blocked:
                return math.sqrt(F * (2 * k + ns0) / (2.0 * (F + nc0)))
            T = 2 * k + nc0 + ns0
            Q = (math.sqrt(F + T) - math.sqrt(F)) ** 2
            return (Q * F / 4.0) ** 0.25
        try:
            alpha = float(word)
        except ValueError:
            raise ParameterError(
                "alpha",
                f"alpha must be 'rotatable', 'orthogonal', 'face', 'practical' or a positive number "
                f"(got {alpha!r})"
            ) from None
    try:
        a = float(alpha)
    except (TypeError, ValueError):
        raise ParameterError("alpha", f"alpha must be a positive number (got {alpha!r})") from None
    if not (math.isfinite(a) and a > 0):
        raise ParameterError("alpha", f"alpha must be a positive number (got {alpha!r})")
    return a


def _alpha_rule(alpha: Any) -> str:
    if isinstance(alpha, str):
        a = alpha.strip().lower()
        for full in ("rotatable", "orthogonal", "practical", "face"):
            if a in (full, full[0]) or (full == "face" and a == "faced"):
                return full
    return "given"


def _centers(center: Any, blocked: bool) -> tuple[int, int]:
    if isinstance(center, (tuple, list)):
        if len(center) != 2:
            raise ParameterError("center", "center must be one number or a pair (cube centre runs, star centre runs)")
        return check_center(center[0]), check_center(center[1])
    c = check_center(center)
    return (c, c) if blocked else (c, 0)


def central_composite(
    factors: Any,
    alpha: Any = None,
    face: str = "circumscribed",
    center: Any = (4, 4),
    blocks: int | None = None,
    seed: Any = None,
    randomize: bool = True,
) -> Design:
    """Central composite design with a full 2^k cube (2 to 10 factors).

    Parameters
    ----------
    factors : FactorSpace, mapping or list
        As for :func:`~rsm_lrg.design.box_behnken`; low/high [factor units] are coded ±1.
    alpha : {"rotatable", "orthogonal", "practical", "face"}, float or None
        Star distance rule (see the module docstring). ``None``: ``"rotatable"``, or 1 with
        ``face="faced"``.
    face : {"circumscribed", "inscribed", "faced"}
        Also accepted: ``"ccc"``, ``"cci"``, ``"ccf"``.
    center : int or (int, int)
        Centre runs with the cube and with the star points. One number: all centre runs
        after the cube when unblocked, that many in each block when blocked.
    blocks : None, 1 or 2
        2: cube runs (+ their centre runs) in block 1, star runs (+ theirs) in block 2.
    seed, randomize
        As for :func:`~rsm_lrg.design.box_behnken` (randomised within blocks).

    Returns
    -------
    Design
        Standard order: cube (Yates order), cube centres, star (−α, +α for A, then B, ...),
        star centres. ``options["alpha"]`` is α in the units of the circumscribed design.

    Examples
    --------
    >>> d = central_composite({"x": (0, 1), "y": (0, 1), "z": (0, 1)}, center=(3, 3), randomize=False)
    >>> d.n_runs, round(d.options["alpha"], 3)
    (20, 1.682)
    """
    space = as_factor_space(factors)
    k = numeric_part(space)[1]
    if not 2 <= k <= _MAX_K:
        raise ValueError(f"a central composite design needs 2 to {_MAX_K} factors (got {k})")
    if not isinstance(face, str) or face.strip().lower() not in _FACES:
        raise ParameterError("face", f"face must be 'circumscribed', 'inscribed' or 'faced' (got {face!r})")
    face_n = _FACES[face.strip().lower()]
    nb = 1 if blocks is None else blocks
    if isinstance(nb, (bool, np.bool_)) or nb not in (1, 2):
        raise ValueError(f"a central composite design can have 1 block or 2 (cube and star), got {blocks!r}")
    blocked = nb == 2
    nc0, ns0 = _centers(center, blocked)
    if face_n == "faced":
        if alpha is not None and _alpha_rule(alpha) != "face" and ccd_alpha(k, alpha) != 1.0:
            raise ValueError(f"a face-centred design has alpha = 1; alpha {alpha!r} contradicts face='faced'")
        alpha = "face"
    elif alpha is None:
        alpha = "rotatable"
    a = ccd_alpha(k, alpha, (nc0, ns0), blocked)
    if _alpha_rule(alpha) == "face":
        face_n = "faced"

    from pyDOE3 import ff2n

    cube = np.asarray(ff2n(k), dtype=float)
    cube = cube[np.lexsort(cube.T)]  # Yates order, first factor fastest
    star = np.zeros((2 * k, k))
    for i in range(k):
        star[2 * i, i], star[2 * i + 1, i] = -a, a
    parts = [cube, np.zeros((nc0, k)), star, np.zeros((ns0, k))]
    coded = np.vstack(parts)
    if face_n == "inscribed":
        coded = coded / a
    bstd = None
    if blocked:
        bstd = np.concatenate([np.full(len(cube) + nc0, 1), np.full(2 * k + ns0, 2)])
    options = {
        "alpha": a,
        "alpha_rule": _alpha_rule(alpha),
        "face": face_n,
        "center": [nc0, ns0],
        "blocks": nb,
        "cube_runs": int(len(cube)),
        "star_runs": 2 * k,
    }
    coded, bstd = cross_categoric(space, coded, bstd)
    return Design.from_standard(space, "central-composite", coded, blocks_std=bstd, seed=seed,
                                randomize=randomize, options=options)
