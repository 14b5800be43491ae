"""Mixture designs: simplex lattice, simplex centroid and extreme vertices (issue 22).

In a mixture the factors are the proportions ``x_1, ..., x_q`` of a blend; they sum to the
total ``T`` (1 for fractions, 100 for percent, a batch mass) so the region is a simplex,
often cut down by lower and upper bounds and other linear constraints.

Designs (Cornell, *Experiments with Mixtures*, 3rd ed., 2002, ch. 2-4)
-----------------------------------------------------------------------
:func:`simplex_lattice`
    The ``{q, m}`` lattice (Scheffé 1958): every blend whose proportions are ``0, 1/m, ...,
    1`` of the total, ``C(q + m - 1, m)`` points; ``center`` adds the overall centroid
    ``(1/q, ..., 1/q)`` once and ``axial`` the ``q`` axial check blends ``((q + 1)/2q,
    1/2q, ..., 1/2q)`` (Cornell 2002, sec. 2.16).
:func:`simplex_centroid`
    The ``2^q - 1`` centroids of the simplex's faces (Scheffé 1963): the pure blends, the
    50:50 binary blends, ..., the overall centroid.
:func:`extreme_vertices`
    The vertices of ``{L_i <= x_i <= U_i, sum x_i = T, a_j . x <= b_j}`` (McLean & Anderson
    1966, *Technometrics* 8, 447-454), found by enumeration: every choice of ``q - 1``
    constraint planes (bounds and linear constraints) is solved with ``sum x = T``, the
    feasible solutions are kept and duplicates (within 1e-12 of the total) merged.
    ``centroids=True`` adds the edge centroids, the constraint-plane (facet, dimension
    ``q - 2``) centroids and the overall centroid, each the average of the vertices on it
    (as Design-Expert's extreme-vertices design; faces of the dimensions between 2 and
    ``q - 3`` are not added).

Every generator returns a :class:`MixtureDesign`, a :class:`~rsm_lrg.design.Design` whose
actual columns are the real proportions at full precision (every run sums to ``T`` to
within ``1e-12 * T``), in standard order then randomised run order as other designs.

The coded columns
-----------------
A mixture's coded column ``coded_A`` is the **L-pseudo component** (Cornell 2002, sec.
3.3) ``z_i = (x_i - L_i) / (T - sum L)``, between 0 and 1, with ``L_i`` the lower bound
(the implied one for extreme vertices; 0 for a lattice or centroid, where ``z_i = x_i / T``).
It is held, as every design's coded value, to 12 decimals. The factor attached to
component ``i`` is the linear coding with coded 0 at ``L_i`` and coded 1 at
``L_i + (T - sum L)``, so that :func:`~rsm_lrg.design.read_design` pairs the columns back;
its ``low``/``high`` (coded -1/+1) are ``L_i -/+ (T - sum L)``, a coding device, not the
component's bounds (those are in ``options["bounds"]``).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import Factor, FactorSpace, letters_for
from ..factors.factor import check_factor_name
from .core import BLOCK_COLUMN, CODED_PREFIX, Design, as_factor_space, randomized_run_order, seeded_options

__all__ = [
    "MixtureDesign",
    "simplex_lattice",
    "simplex_centroid",
    "extreme_vertices",
    "lattice_size",
    "candidate_blends",
    "CandidateSet",
    "cross_process",
    "process_space",
    "MAX_RUNS",
    "MAX_COMPONENTS",
    "MAX_PLANE_CHOICES",
]

#: Most runs a mixture generator writes (a lattice or centroid design beyond it is refused).
MAX_RUNS = 20000
#: Most components of an extreme-vertices design (as R mixexp's ``Xvert``).
MAX_COMPONENTS = 12
#: Most choices of ``q - 1`` constraint planes the vertex enumeration tries.
MAX_PLANE_CHOICES = 3_000_000
#: Tolerance of the sum and of duplicate points, relative to the total [-].
SUM_RTOL = 1e-12
#: Feasibility tolerance of a candidate vertex, relative to the size of the constraint [-].
FEAS_RTOL = 1e-9


@dataclass(frozen=True, eq=False)
class MixtureDesign(Design):
    """A mixture design: a :class:`~rsm_lrg.design.Design` that also holds the real
    proportions.

    Attributes
    ----------
    proportions : numpy.ndarray, shape (n, q)
        The real proportions [units of the total], rows in run order; each row sums to
        ``total``. They are the CSV's actual columns, written at full precision.
    total : float
        The total the proportions sum to [units of the total; 1 for fractions].
    point_types : tuple of str
        Per run (run order): ``"vertex"``, ``"edge"``, ``"plane"``, ``"centroid"``,
        ``"axial"``, ``"lattice"``, ``"third"`` (a point at a third of an edge) or
        ``"blend"`` (a simplex-centroid face centroid).

    The coded runs are the L-pseudo components (see the module docstring). A mixture-process
    design has process factors after the components (``factors[q:]``, numeric, coded -1 to
    +1 as every factor); ``proportions`` then has the ``q`` component columns only.
    """

    proportions: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    total: float = 1.0
    point_types: tuple = ()

    def __post_init__(self) -> None:
        run = np.asarray(self.run_order, dtype=int)
        order = np.argsort(run, kind="stable")
        props = np.array(self.proportions, dtype=float)
        n, k = np.asarray(self.coded_runs).shape
        if props.ndim != 2 or props.shape[0] != n or not 2 <= props.shape[1] <= k:
            raise ValueError(f"proportions must be an ({n}, q) array with 2 <= q <= {k}, got shape {props.shape}")
        types = tuple(self.point_types) if self.point_types else ("blend",) * n
        if len(types) != n:
            raise ValueError(f"point_types must give one type per run ({n})")
        super().__post_init__()
        props = props[order]
        props.setflags(write=False)
        object.__setattr__(self, "proportions", props)
        object.__setattr__(self, "point_types", tuple(types[i] for i in order))
        object.__setattr__(self, "total", float(self.total))

    @property
    def n_center(self) -> int:
        """Number of runs at the overall centroid."""
        return sum(t == "centroid" for t in self.point_types)

    @property
    def n_components(self) -> int:
        """Number of mixture components (the factors after them are process factors)."""
        return int(self.proportions.shape[1])

    @property
    def actual(self):
        """The real proportions (and the process factors' actual settings) as a DataFrame
        keyed by name, in run order."""
        import pandas as pd

        q = self.n_components
        out = pd.DataFrame({f.name: self.proportions[:, i].copy() for i, f in enumerate(self.factors) if i < q})
        if q < self.n_factors:
            process = super().actual
            for f in list(self.factors)[q:]:
                out[f.name] = process[f.name].to_numpy()
        return out

    def csv_text(self) -> str:
        """The design CSV: ``std_order, run_order, coded_A, ...`` (L-pseudo components, then
        the process factors coded) and one column per component with the real proportion
        (shortest round-trip text), then the process factors' actual settings.

        Returns
        -------
        str
            The CSV text, header first, one line per run (run order).
        """
        import csv
        import io

        columns: dict[str, list[str]] = {"std_order": [str(int(v)) for v in self.std_order],
                                         "run_order": [str(int(v)) for v in self.run_order]}
        if self.blocks is not None:
            columns[BLOCK_COLUMN] = [str(v) for v in self.blocks.tolist()]
        for i, f in enumerate(self.factors):
            c = self.coded_runs[:, i]
            columns[CODED_PREFIX + f.letter] = ([str(int(v)) for v in c] if np.all(c == np.round(c))
                                                else [repr(float(v)) for v in c])
        actual = self.actual
        for f in self.factors:
            columns[f.name] = [repr(float(v)) for v in actual[f.name]]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(list(columns))
        w.writerows(zip(*columns.values()))
        return buf.getvalue()

    def check_finite(self) -> None:
        """ValueError when a proportion is not finite (never, from the generators)."""
        if not np.all(np.isfinite(self.proportions)):
            raise ValueError("the design holds a non-finite proportion; nothing was written")

    def summary(self) -> str:
        """A few lines for people: kind, components, runs by type, seed, notes.

        Returns
        -------
        str
            Text for people, several lines.
        """
        o = self.options
        q = self.n_components
        counts: dict[str, int] = {}
        for i in np.argsort(self.std_order, kind="stable"):
            counts[self.point_types[i]] = counts.get(self.point_types[i], 0) + 1
        kinds = ", ".join(f"{v} {k}" for k, v in counts.items())
        process = list(self.factors)[q:]
        lines = [f"{self.kind} design: {q} components"
                 + (f" and {len(process)} process factor{'s' * (len(process) > 1)}" if process else "")
                 + f", {self.n_runs} runs ({kinds}), total {self.total:g}"
                 + (f", {self.n_blocks} blocks" if self.blocks is not None else "")]
        if o.get("constraints"):
            lines.append("constraints: " + "; ".join(o["constraints"]))
        for note in o.get("notes", []):
            lines.append(str(note))
        if not o.get("randomize", True):
            lines.append("run order: standard order (not randomised)")
        elif o.get("seed") is not None:
            lines.append(f"run order: randomised{' within blocks' if self.blocks is not None else ''}, seed {o['seed']}")
        else:
            lines.append("run order: randomised from a numpy Generator")
        bounds = o.get("bounds", {})
        lows = o.get("pseudo_lows", {})
        for f in list(self.factors)[:q]:
            lo, hi = bounds.get(f.name, (0.0, self.total))
            lines.append(f"  {f.letter} {f.name}: {lo:.12g} .. {hi:.12g} (L-pseudo lower bound {lows.get(f.name, 0.0):.12g})")
        for f in process:
            lines.append(f"  {f.letter} {f.name}: process factor, {f.low:.12g} .. {f.high:.12g} (coded -1 .. +1)")
        lines.append("coded columns: L-pseudo components (x - L) / (total - sum L)"
                     + (", process factors coded -1 .. +1" if process else ""))
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (f"MixtureDesign(kind={self.kind!r}, components={self.factors.names[:self.n_components]!r}, "
                f"n_runs={self.n_runs}, total={self.total:g})")


# -- helpers -------------------------------------------------------------------------------
def _total(total: Any) -> float:
    if isinstance(total, (bool, np.bool_)):
        raise ParameterError("total", "total must be a number")
    try:
        t = float(total)
    except (TypeError, ValueError):
        raise ParameterError("total", f"total must be a number, not {total!r}") from None
    if not (math.isfinite(t) and t > 0):
        raise ParameterError("total", f"total must be a finite number > 0 (got {total!r})")
    if t < MIN_TOTAL or t > MAX_TOTAL:  # shares of a tiny total lose their digits (subnormal floats)
        raise ParameterError("total", f"total must lie between {MIN_TOTAL:g} and {MAX_TOTAL:g}, so that every share "
                                      f"of a blend keeps its digits (got {t:g})")
    return t


#: The range of a mixture's total: a blend's shares (the total times fractions such as 1/12) must
#: stay normal floats, and their sums finite.
MIN_TOTAL = 1e-290
MAX_TOTAL = 1e290


def _names(components: Any, minimum: int = 2) -> list[str]:
    """Component names: strings, none empty or repeated, at least ``minimum`` of them."""
    if isinstance(components, (str, bytes)):
        raise TypeError("components must be a list of names, not a single string")
    try:
        names = list(components)
    except TypeError:
        raise TypeError(f"components must be a list of names, not {type(components).__name__}") from None
    out: list[str] = []
    for n in names:
        if not isinstance(n, str):
            raise TypeError(f"component names must be strings, not {type(n).__name__}")
        if not n.strip():
            raise ParameterError("components", "an empty name")
        if "=" in n:
            raise ParameterError("components", f"component {n!r}: a lattice or centroid design takes bare names "
                             "(bounds belong to an extreme-vertices design)")
        check_factor_name(n)
        if n in out:
            raise ParameterError("components", f"component {n!r} is given twice")
        out.append(n)
    if len(out) < minimum:
        raise ValueError(f"a mixture needs at least {minimum} components (got {len(out)})")
    return out


def lattice_size(q: int, m: int) -> int:
    """Number of points of the ``{q, m}`` simplex lattice, ``C(q + m - 1, m)``.

    >>> lattice_size(3, 2), lattice_size(4, 3)
    (6, 20)
    """
    return math.comb(q + m - 1, m)


def _compositions(q: int, m: int) -> list[tuple[int, ...]]:
    """The ``q``-part compositions of ``m`` (parts >= 0), vertices first, then by the number
    of non-zero parts, each group in descending lexicographic order."""
    out = [c + (m - sum(c),) for c in itertools.product(range(m + 1), repeat=q - 1) if sum(c) <= m]
    return sorted(out, key=lambda c: (sum(1 for v in c if v), tuple(-v for v in c)))


def finish_mixture(kind: str, names: list[str], props_std: np.ndarray, types_std: list[str], total: float,
            lows: np.ndarray, *, seed: Any, randomize: bool, options: dict, process: Any = None,
            process_coded: np.ndarray | None = None, blocks: np.ndarray | None = None) -> MixtureDesign:
    """Assign standard and run order and build the design (pseudo coding from ``lows``);
    ``process`` (factors) and ``process_coded`` (their coded settings per run, standard order)
    for a mixture-process design; ``blocks`` (1..b per run, standard order, block by block):
    the run order is randomised within each block. ``props_std``: the real proportions,
    standard order."""
    n, q = props_std.shape
    if n > MAX_RUNS:
        raise ParameterError("runs", f"the design would have {n} runs; at most {MAX_RUNS} are written")
    r = total - math.fsum(lows.tolist())
    proc = list(process.factors) if process is not None else []
    letters = letters_for(q + len(proc))
    space = FactorSpace(tuple(Factor(nm, float(lo) - r, float(lo) + r, L)
                              for nm, lo, L in zip(names, lows, letters))
                        + tuple(replace(f, letter=L) for f, L in zip(proc, letters[q:])))
    coded = (props_std - lows[None, :]) / r
    if proc:
        coded = np.hstack([coded, np.asarray(process_coded, dtype=float).reshape(n, len(proc))])
    rng, opts = seeded_options(options, seed, randomize)
    opts["total"] = total
    opts["pseudo_lows"] = {nm: float(lo) for nm, lo in zip(names, lows)}
    bl = None if blocks is None else np.asarray(blocks, dtype=int)
    perm = randomized_run_order(bl, n, rng)
    run_order = np.empty(n, dtype=int)
    run_order[perm] = np.arange(1, n + 1)
    return MixtureDesign(space, kind, coded, np.arange(1, n + 1), run_order, bl, opts,
                         proportions=props_std, total=total, point_types=tuple(types_std))


def _scaled(total: float, num: int, den: int) -> float:
    """``total * num / den``, correctly rounded."""
    return float(Fraction(total) * Fraction(num, den))


def _extra_blends(q: int, total: float, center: bool, axial: bool) -> tuple[list[list[float]], list[str]]:
    rows: list[list[float]] = []
    types: list[str] = []
    if axial:
        for i in range(q):
            rows.append([_scaled(total, q + 1, 2 * q) if j == i else _scaled(total, 1, 2 * q) for j in range(q)])
            types.append("axial")
    if center:
        rows.append([_scaled(total, 1, q)] * q)
        types.append("centroid")
    return rows, types


# -- simplex lattice and centroid ----------------------------------------------------------
def simplex_lattice(components: Sequence[str], degree: int, center: bool = False, axial: bool = False,
                    total: float = 1.0, *, seed: Any = None, randomize: bool = True) -> MixtureDesign:
    """The ``{q, m}`` simplex-lattice design (Scheffé 1958; Cornell 2002, sec. 2.2).

    Parameters
    ----------
    components : sequence of str
        The component names (``q >= 2``), in order; they get the letters A, B, ...
    degree : int
        The lattice degree ``m >= 1``: the proportions take the values ``0, T/m, ..., T``.
    center : bool
        Add one run at the overall centroid ``(T/q, ..., T/q)`` (a replicate when the
        lattice holds it already, as ``{3, 3}`` does).
    axial : bool
        Add the ``q`` axial check blends: component ``i`` at ``T (q + 1) / 2q``, the others
        at ``T / 2q`` (Cornell 2002, sec. 2.16).
    total : float
        The total ``T`` the proportions sum to [units of the proportions; default 1].
    seed, randomize
        Run order as for every design (:meth:`~rsm_lrg.design.Design.from_standard`).

    Returns
    -------
    MixtureDesign
        ``C(q + m - 1, m)`` lattice runs (then the axial, then the centroid run) in standard
        order, randomised in run order.

    >>> d = simplex_lattice(["a", "b", "c"], 2, randomize=False)
    >>> d.n_runs, d.proportions.sum(axis=1).tolist()
    (6, [1.0, 1.0, 1.0, 1.0, 1.0, 1.0])
    """
    names = _names(components)
    if isinstance(degree, (bool, np.bool_)) or not isinstance(degree, (int, np.integer)):
        raise ParameterError("degree", f"degree must be a whole number, not {degree!r}")
    m = int(degree)
    if m < 1:
        raise ParameterError("degree", f"degree must be at least 1 (got {m})")
    t = _total(total)
    q = len(names)
    size = lattice_size(q, m)
    if size > MAX_RUNS:
        raise ParameterError("runs", f"the {{{q}, {m}}} lattice has {size} points; at most {MAX_RUNS} are written")
    comps = _compositions(q, m)
    rows = [[_scaled(t, v, m) for v in c] for c in comps]
    types = ["vertex" if max(c) == m else "centroid" if q * min(c) == m and len(set(c)) == 1 else "lattice"
             for c in comps]
    extra, extra_types = _extra_blends(q, t, bool(center), bool(axial))
    props = np.array(rows + extra, dtype=float)
    return finish_mixture("simplex-lattice", names, props, types + extra_types, t, np.zeros(q), seed=seed,
                   randomize=randomize,
                   options={"degree": m, "center": bool(center), "axial": bool(axial),
                            "bounds": {nm: (0.0, t) for nm in names}})


def simplex_centroid(components: Sequence[str], center: bool = False, axial: bool = False, total: float = 1.0,
                     *, seed: Any = None, randomize: bool = True) -> MixtureDesign:
    """The simplex-centroid design (Scheffé 1963; Cornell 2002, sec. 2.13): ``2^q - 1`` runs.

    Every non-empty subset ``S`` of the components gives the blend with ``T / |S|`` of each
    component of ``S`` and 0 of the others: the ``q`` pure blends, the ``C(q, 2)`` 50:50
    blends, ..., the overall centroid. ``axial`` adds the ``q`` axial check blends as
    :func:`simplex_lattice` does; ``center`` adds a replicate of the overall centroid.

    Parameters
    ----------
    components : sequence of str
        The component names (``q >= 2``).
    center, axial : bool
        Extra runs (see above).
    total : float
        The total ``T`` [units of the proportions; default 1].
    seed, randomize
        Run order as for every design.

    Returns
    -------
    MixtureDesign
        The blends as real proportions and L-pseudo components, in run order.

    Notes
    -----
    >>> simplex_centroid(["a", "b", "c", "d"], randomize=False).n_runs
    15
    """
    names = _names(components)
    t = _total(total)
    q = len(names)
    if 2 ** q - 1 > MAX_RUNS:
        raise ParameterError("runs", f"a simplex-centroid design in {q} components has {2 ** q - 1} runs; "
                         f"at most {MAX_RUNS} are written")
    rows: list[list[float]] = []
    types: list[str] = []
    for size in range(1, q + 1):
        for subset in itertools.combinations(range(q), size):
            v = _scaled(t, 1, size)
            rows.append([v if j in subset else 0.0 for j in range(q)])
            types.append("vertex" if size == 1 else "centroid" if size == q else "blend")
    extra, extra_types = _extra_blends(q, t, bool(center), bool(axial))
    props = np.array(rows + extra, dtype=float)
    return finish_mixture("simplex-centroid", names, props, types + extra_types, t, np.zeros(q), seed=seed,
                   randomize=randomize,
                   options={"center": bool(center), "axial": bool(axial),
                            "bounds": {nm: (0.0, t) for nm in names}})


# -- extreme vertices ----------------------------------------------------------------------
def _bounds(bounds: Any, t: float) -> tuple[list[str], np.ndarray, np.ndarray]:
    if isinstance(bounds, Mapping):
        items = list(bounds.items())
    else:
        if isinstance(bounds, (str, bytes)):
            raise TypeError("bounds must be a mapping {name: (low, high)} or a list of (name, low, high)")
        items = [(it[0], (it[1], it[2])) for it in bounds]
    names: list[str] = []
    lo: list[float] = []
    hi: list[float] = []
    for name, pair in items:
        if not isinstance(name, str) or not name.strip():
            raise ParameterError("bounds", f"an empty or non-text name ({name!r})")
        check_factor_name(name)
        if name in names:
            raise ParameterError("bounds", f"component {name!r} is given twice")
        try:
            a, b = (float(v) for v in pair)
        except (TypeError, ValueError):
            raise ParameterError("bounds", f"component {name!r}: bounds must be two numbers LOW, HIGH (got {pair!r})") from None
        if not (math.isfinite(a) and math.isfinite(b)):
            raise ParameterError("bounds", f"component {name!r}: bounds must be finite (got {a!r}, {b!r})")
        if a < 0:
            raise ParameterError("bounds", f"component {name!r}: LOW {a:g} is negative; a proportion is at least 0")
        if a > b:
            raise ParameterError("bounds", f"component {name!r}: LOW {a:g} is above HIGH {b:g}")
        if a == b:
            raise ParameterError("bounds", f"component {name!r}: LOW equals HIGH ({a:g}); a fixed component is not a "
                             "mixture variable (take it out and lower the total)")
        if a >= t:
            raise ParameterError("bounds", f"component {name!r}: LOW {a:g} is not below the total {t:g}")
        names.append(name)
        lo.append(a)
        hi.append(b)
    if len(names) < 2:
        raise ValueError(f"a mixture needs at least 2 components (got {len(names)})")
    if len(names) > MAX_COMPONENTS:
        raise ValueError(f"an extreme-vertices design takes at most {MAX_COMPONENTS} components (got {len(names)})")
    L, U = np.array(lo), np.array(hi)
    sl, su = math.fsum(lo), math.fsum(hi)
    tol = SUM_RTOL * t
    if sl > t + tol:
        raise ParameterError("bounds", "component bounds: the lower bounds sum to "
                         f"{sl:.12g} > total {t:g} (" + ", ".join(f"{n} {v:g}" for n, v in zip(names, lo)) + ")")
    if su < t - tol:
        raise ParameterError("bounds", "component bounds: the upper bounds sum to "
                         f"{su:.12g} < total {t:g} (" + ", ".join(f"{n} {v:g}" for n, v in zip(names, hi)) + ")")
    return names, L, U


def _linear_constraints(constraints: Any, names: list[str], L: np.ndarray, U: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """``(A, b, texts)`` with ``A x <= b`` in actual proportions."""
    from .constraints import Constraints

    q = len(names)
    if constraints is None:
        return np.zeros((0, q)), np.zeros(0), []
    if isinstance(constraints, Constraints):
        cons = constraints
        if cons.space.names != names:
            raise ParameterError("constraints", "built on other factors than the components")
    else:
        space = FactorSpace.from_ranges([(n, float(a), float(b)) for n, a, b in zip(names, L, U)])
        cons = Constraints.parse(constraints, space, check_empty=False)
    for c in cons.items:
        if not c.is_linear:
            raise ParameterError("constraints", f"constraint {c.text!r} is not linear in the proportions; extreme vertices "
                             "need linear constraints")
    if not len(cons):
        return np.zeros((0, q)), np.zeros(0), []
    A, b = cons.linear_system(coded=False)
    for j, c in enumerate(cons.items):
        if not np.all(np.isfinite(A[j])) or not math.isfinite(float(b[j])):
            raise ParameterError("constraints", f"constraint {c.text!r}: its coefficients are not finite")
        if not np.any(A[j] != 0):
            raise ParameterError("constraints", f"constraint {c.text!r} holds no component")
    return A, b, cons.expressions


def _dedupe(points: np.ndarray, tol: float) -> np.ndarray:
    """Indices of the first of each group of points within ``tol`` (max norm) of each other."""
    keep: list[int] = []
    for i, p in enumerate(points):
        if not keep or np.min(np.max(np.abs(points[keep] - p), axis=1)) > tol:
            keep.append(i)
    return np.array(keep, dtype=int)


def _mean(P: np.ndarray) -> np.ndarray:
    """The average of the rows of ``P``, each coordinate computed exactly and rounded once."""
    n = len(P)
    return np.array([float(sum((Fraction(float(x)) for x in col), Fraction(0)) / n) for col in P.T])


def _affine_rank(P: np.ndarray, tol: float) -> int:
    if len(P) <= 1:
        return 0
    s = np.linalg.svd(P[1:] - P[0], compute_uv=False)
    return int(np.sum(s > tol))


def _vertices(G: np.ndarray, h: np.ndarray, t: float, L: np.ndarray, U: np.ndarray) -> np.ndarray:
    """The vertices of ``{G x <= h, sum x = t}`` by enumeration of ``q - 1`` active rows."""
    m, q = G.shape
    choices = math.comb(m, q - 1)
    if choices > MAX_PLANE_CHOICES:
        raise ParameterError("constraints", f"{m} constraint planes in {q} components give {choices} choices of "
                         f"{q - 1} planes to try; at most {MAX_PLANE_CHOICES}")
    scale = np.abs(G) @ np.maximum(np.abs(L), np.abs(U)) + np.abs(h)
    found: list[np.ndarray] = []
    combos = itertools.combinations(range(m), q - 1)
    chunk = 20000
    ones = np.ones((1, q))
    while True:
        block = np.array(list(itertools.islice(combos, chunk)), dtype=int).reshape(-1, q - 1)
        if not len(block):
            break
        M = np.concatenate([G[block], np.broadcast_to(ones, (len(block), 1, q))], axis=1)
        rhs = np.concatenate([h[block], np.full((len(block), 1), t)], axis=1)
        det_ok = np.abs(np.linalg.det(M)) > 1e-12 * np.prod(np.linalg.norm(M, axis=2), axis=1)
        if not det_ok.any():
            continue
        X = np.linalg.solve(M[det_ok], rhs[det_ok][..., None])[..., 0]
        ok = np.all(X @ G.T - h[None, :] <= FEAS_RTOL * scale[None, :], axis=1)
        found.extend(X[ok])
    if not found:
        return np.zeros((0, q))
    V = np.array(found)
    # snap the proportions at a bound onto it exactly; a single free proportion takes the rest
    tol = FEAS_RTOL * max(t, float(np.max(U)))
    at_low = np.abs(V - L[None, :]) <= tol
    at_high = (np.abs(V - U[None, :]) <= tol) & ~at_low
    V = np.where(at_low, L[None, :], np.where(at_high, U[None, :], V))
    free = ~(at_low | at_high)
    V, first = np.unique(V, axis=0, return_index=True)
    free = free[first]
    for v, f in zip(V, free):
        if f.sum() == 1:
            j = int(np.flatnonzero(f)[0])
            v[j] = float(Fraction(t) - sum(Fraction(float(x)) for x in np.delete(v, j)))
    V = V[_dedupe(V, SUM_RTOL * t)]
    order = np.lexsort(V.T[::-1])
    return V[order]


def _active(V: np.ndarray, G: np.ndarray, h: np.ndarray, L: np.ndarray, U: np.ndarray) -> np.ndarray:
    """``(n_vertices, m)`` booleans: which constraint rows are active at each vertex."""
    scale = np.abs(G) @ np.maximum(np.abs(L), np.abs(U)) + np.abs(h)
    return np.abs(V @ G.T - h[None, :]) <= FEAS_RTOL * scale[None, :]


@dataclass(frozen=True)
class _Region:
    """The constrained mixture region ``{L <= x <= U, sum x = T, A x <= b}``: its vertices
    and the constraint rows ``G x <= h`` (bounds first) that are active at each."""

    names: list[str]
    lower: np.ndarray
    upper: np.ndarray
    total: float
    texts: list[str]
    G: np.ndarray
    h: np.ndarray
    vertices: np.ndarray
    active: np.ndarray

    def edges(self) -> list[tuple[int, int]]:
        """The pairs of vertices joined by an edge (``q - 2`` common active planes of rank
        ``q - 2`` besides the sum)."""
        q = len(self.names)
        ones = np.ones((1, q))
        out = []
        for i, j in itertools.combinations(range(len(self.vertices)), 2):
            common = self.active[i] & self.active[j]
            if common.sum() >= q - 2 and np.linalg.matrix_rank(np.vstack([ones, self.G[common]])) == q - 1:
                out.append((i, j))
        return out

    def planes(self) -> list[np.ndarray]:
        """Per constraint plane that bounds a facet (dimension ``q - 2``): which vertices lie on it."""
        q = len(self.names)
        out = []
        for j in range(self.G.shape[0]):
            on = self.active[:, j]
            if on.sum() >= q - 1 and _affine_rank(self.vertices[on], 1e-9 * self.total) == q - 2:
                out.append(on)
        return out


def _region(bounds: Any, constraints: Any, t: float) -> _Region:
    """Check the bounds and constraints and enumerate the vertices (see :func:`extreme_vertices`)."""
    names, L, U = _bounds(bounds, t)
    q = len(names)
    A, b, texts = _linear_constraints(constraints, names, L, U)
    eye = np.eye(q)
    G = np.vstack([-eye, eye, A])
    h = np.concatenate([-L, U, b])
    labels = [f"{n} >= {lo:.12g}" for n, lo in zip(names, L)] + [f"{n} <= {hi:.12g}" for n, hi in zip(names, U)]
    labels += texts
    V = _vertices(G, h, t, L, U)
    if not len(V):
        which = f" and the constraints {'; '.join(texts)}" if texts else ""
        raise ParameterError("constraints", f"the region of the bounds{which} is empty: no blend summing to {t:g} "
                         "satisfies them all")
    act = _active(V, G, h, L, U)
    rank = _affine_rank(V, 1e-9 * t)
    if rank < q - 1:
        tight = [labels[j] for j in range(len(labels)) if act[:, j].all()]
        raise ParameterError("constraints", f"the region has no interior (dimension {rank}, a mixture of {q} "
                         f"components needs {q - 1}): every blend in it has {'; '.join(tight) or 'a fixed proportion'}")
    return _Region(names, L, U, t, texts, G, h, V, act)


@dataclass(frozen=True)
class CandidateSet:
    """The candidate blends of a constrained mixture region (:func:`candidate_blends`).

    Attributes
    ----------
    names : list of str
        The components.
    points : numpy.ndarray, shape (m, q)
        The candidate proportions [units of the total], each row summing to ``total``.
    types : list of str
        ``"vertex"``, ``"edge"``, ``"third"``, ``"plane"``, ``"centroid"`` or ``"axial"``.
    lows : numpy.ndarray, shape (q,)
        The L-pseudo lower bounds (the given ones, or the implied ones where the region
        reaches no lower), as :func:`extreme_vertices` codes.
    lower, upper : numpy.ndarray, shape (q,)
        The given bounds.
    G, h : numpy.ndarray
        The region as ``G x <= h`` (bounds, then the linear constraints) with ``sum x = T``.
    texts : list of str
        The linear constraints as given.
    total : float
    """

    names: list[str]
    points: np.ndarray
    types: list[str]
    lows: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    G: np.ndarray
    h: np.ndarray
    texts: list[str]
    total: float

    def inside(self, x: np.ndarray) -> np.ndarray:
        """Whether each row of real proportions ``x`` meets every bound and constraint (within
        ``1e-12`` of each constraint's size) and sums to the total (within ``1e-12 T``)."""
        x = np.atleast_2d(np.asarray(x, dtype=float))
        scale = np.abs(self.G) @ np.maximum(np.abs(self.lower), np.abs(self.upper)) + np.abs(self.h)
        ok = np.all(x @ self.G.T - self.h[None, :] <= 1e-12 * scale[None, :], axis=1)
        return ok & (np.abs(x.sum(axis=1) - self.total) <= SUM_RTOL * self.total)


def candidate_blends(bounds: Mapping[str, tuple[float, float]] | Sequence[tuple[str, float, float]],
                     constraints: Any = None, total: float = 1.0) -> CandidateSet:
    """The candidate blends of an optimal mixture design on a constrained region (as
    Design-Expert's candidate set): the vertices, the edge centroids and the points at a
    third and two thirds of each edge (which a full cubic needs), the constraint-plane
    centroids, the overall centroid and the axial check blends (half way from each vertex
    to the overall centroid; Cornell 2002, sec. 2.16). Each is an exact average of vertices
    rounded once; duplicates within ``1e-12 T`` are merged.

    Returns
    -------
    CandidateSet

    >>> c = candidate_blends({"a": (0, 1), "b": (0, 1), "c": (0, 1)})
    >>> len(c.points), c.types.count("third"), float(c.points.sum(axis=1).max()), bool(c.inside(c.points).all())
    (16, 6, 1.0, True)
    """
    t = _total(total)
    reg = _region(bounds, constraints, t)
    V = reg.vertices
    centre = _mean(V)
    rows: list[np.ndarray] = [V]
    types = ["vertex"] * len(V)

    def weighted(pairs: list[tuple[np.ndarray, int]], den: int) -> np.ndarray:
        """``sum w_i P_i / den`` per coordinate, exactly, rounded once."""
        return np.array([float(sum((Fraction(float(p[c])) * w for p, w in pairs), Fraction(0)) / den)
                         for c in range(len(reg.names))])

    for i, j in reg.edges():
        rows.append(weighted([(V[i], 1), (V[j], 1)], 2)[None, :])
        types.append("edge")
        rows.append(np.array([weighted([(V[i], 2), (V[j], 1)], 3), weighted([(V[i], 1), (V[j], 2)], 3)]))
        types += ["third", "third"]
    for on in reg.planes():
        rows.append(_mean(V[on])[None, :])
        types.append("plane")
    rows.append(centre[None, :])
    types.append("centroid")
    for v in V:
        rows.append(weighted([(v, 1), (centre, 1)], 2)[None, :])
        types.append("axial")
    allp = np.vstack(rows)
    keep = _dedupe(allp, SUM_RTOL * t)
    lows = V.min(axis=0)
    lows = np.where(lows - reg.lower <= SUM_RTOL * t, reg.lower, lows)
    return CandidateSet(reg.names, allp[keep], [types[i] for i in keep], lows, reg.lower, reg.upper, reg.G, reg.h,
                        reg.texts, t)


def extreme_vertices(bounds: Mapping[str, tuple[float, float]] | Sequence[tuple[str, float, float]],
                     constraints: Any = None, centroids: bool = False, total: float = 1.0, *,
                     seed: Any = None, randomize: bool = True) -> MixtureDesign:
    """Extreme-vertices design (McLean & Anderson 1966) of a constrained mixture region.

    The region is ``{L_i <= x_i <= U_i, sum_i x_i = T, a_j . x <= b_j}``. Its vertices are
    enumerated: for every choice of ``q - 1`` planes among the ``2q`` bound planes and the
    linear constraints, the ``q x q`` system with ``sum x = T`` is solved (when it is not
    singular); the solutions that satisfy every constraint (within ``1e-9`` of each
    constraint's size) are the vertices, duplicates within ``1e-12 T`` merged. Proportions
    found at a bound are set to it exactly, and when one proportion alone is not at a bound
    it is ``T`` minus the others, as McLean and Anderson compute them.

    Parameters
    ----------
    bounds : mapping or sequence
        ``{name: (low, high)}`` or ``[(name, low, high), ...]``, the bounds of every
        component in real proportions [units of the total], ``0 <= low < high``.
    constraints : sequence of str, str, Constraints or None
        Linear inequalities in the component names (or letters) and real proportions, e.g.
        ``"a + b <= 0.7"`` (parsed by :class:`~rsm_lrg.design.Constraints`).
    centroids : bool
        Add the edge centroids, the constraint-plane (facet) centroids and the overall
        centroid, each the average of the vertices on it; a centroid that coincides with a
        point already in the design is not repeated.
    total : float
        The total ``T`` [default 1].
    seed, randomize
        Run order as for every design.

    Returns
    -------
    MixtureDesign
        Vertices (then edge, plane and overall centroids) in standard order. The L-pseudo
        coding uses the implied lower bounds (the smallest proportion over the vertices);
        bounds that the region tightens are said in ``options["notes"]``.

    Raises
    ------
    ValueError
        Inconsistent bounds (``low > high``, lower bounds summing above the total, upper
        bounds below it; the message names the components), a nonlinear constraint, an
        empty region or one without interior (lower dimension than ``q - 1``).

    >>> d = extreme_vertices({"Mg": (0.4, 0.6), "NaNO3": (0.1, 0.5), "SrNO3": (0.1, 0.5),
    ...                       "binder": (0.03, 0.08)}, randomize=False)
    >>> d.n_runs
    8
    """
    t = _total(total)
    reg = _region(bounds, constraints, t)
    names, V = reg.names, reg.vertices
    points = [V]
    types = ["vertex"] * len(V)
    if centroids:
        edges = [_mean(V[[i, j]]) for i, j in reg.edges()]
        planes = [_mean(V[on]) for on in reg.planes()]
        extra = [(edges, "edge"), (planes, "plane"), ([_mean(V)], "centroid")]
        for pts, kind in extra:
            if pts:
                points.append(np.array(pts))
                types += [kind] * len(pts)
        allp = np.vstack(points)
        keep = _dedupe(allp, SUM_RTOL * t)
        props = allp[keep]
        types = [types[i] for i in keep]
    else:
        props = V
    L, U, texts = reg.lower, reg.upper, reg.texts
    lows = V.min(axis=0)
    highs = V.max(axis=0)
    notes = []
    tightened = [f"{n} {lo:.12g}..{hi:.12g} (given {gl:.12g}..{gh:.12g})"
                 for n, lo, hi, gl, gh in zip(names, lows, highs, L, U)
                 if lo > gl + SUM_RTOL * t or hi < gh - SUM_RTOL * t]
    if tightened:
        notes.append("implied bounds (the region reaches no further): " + "; ".join(tightened))
    lows = np.where(lows - L <= SUM_RTOL * t, L, lows)
    return finish_mixture("extreme-vertices", names, props, types, t, lows, seed=seed, randomize=randomize,
                   options={"centroids": bool(centroids), "constraints": texts, "notes": notes,
                            "n_vertices": int(len(V)),
                            "bounds": {n: (float(lo), float(hi)) for n, lo, hi in zip(names, L, U)},
                            "implied_bounds": {n: (float(lo), float(hi))
                                               for n, lo, hi in zip(names, V.min(axis=0), highs)}})


# -- mixture-process designs ---------------------------------------------------------------
def process_space(factors: Any, components: Sequence[str]) -> FactorSpace:
    """The process factors of a mixture-process design (``"NAME=LOW:HIGH"`` specs, numeric),
    checked against the component names."""
    space = as_factor_space(factors)
    for f in space.factors:
        if f.kind != "numeric":
            raise ParameterError("factors", f"factor {f.name!r} is categoric; a mixture-process design takes numeric process "
                             "factors")
        if f.name in components:
            raise ParameterError("factors", f"factor {f.name!r} is also a component")
    return space


def cross_process(design: MixtureDesign, factors: Any, *, seed: Any = None, randomize: bool = True) -> MixtureDesign:
    """The crossed mixture-process design (Cornell 2002, ch. 7): every blend of ``design``
    at every point of the two-level full factorial in the process ``factors`` (coded -1, +1;
    standard order, the first factor changing fastest), ``n_blends * 2^k`` runs.

    Parameters
    ----------
    design : MixtureDesign
        A mixture design without process factors (its blends in standard order).
    factors : sequence of str, mapping or FactorSpace
        Numeric process factors, ``"NAME=LOW:HIGH"`` (letters after the components).
    seed, randomize
        Run order of the crossed design, as for every design.

    Returns
    -------
    MixtureDesign
        ``n_blends * 2^k`` runs: every blend at every process setting.

    Notes
    -----
    >>> d = cross_process(simplex_centroid(["a", "b", "c"], randomize=False), ["t=20:40"], randomize=False)
    >>> d.n_runs, d.actual.iloc[:2].to_dict("list")
    (14, {'a': [1.0, 1.0], 'b': [0.0, 0.0], 'c': [0.0, 0.0], 't': [20.0, 40.0]})
    """
    if not isinstance(design, MixtureDesign):
        raise TypeError("design must be a MixtureDesign")
    q = design.n_components
    if q < design.n_factors:
        raise ParameterError("factors", "the design already has process factors")
    names = list(design.factors.names)
    space = process_space(factors, names)
    k = len(space)
    if len(design.std_order) * 2 ** k > MAX_RUNS:
        raise ParameterError("runs", f"{len(design.std_order)} blends at 2^{k} process points are "
                         f"{len(design.std_order) * 2 ** k} runs; at most {MAX_RUNS} are written")
    pts = np.array(list(itertools.product([-1.0, 1.0], repeat=k)))[:, ::-1]
    order = np.argsort(design.std_order, kind="stable")
    P = design.proportions[order]
    types = [design.point_types[i] for i in order for _ in range(len(pts))]
    lows_map = design.options.get("pseudo_lows", {})
    lows = np.array([float(lows_map.get(nm, 0.0)) for nm in names])
    opts = {key: v for key, v in design.options.items() if key not in ("seed", "randomize")}
    opts["notes"] = list(opts.get("notes", [])) + [
        f"crossed mixture-process design: each of the {len(P)} blends at each of the {len(pts)} points of the "
        f"2^{k} factorial in {', '.join(space.names)} (coded -1, +1)"]
    opts["process"] = {f.name: (float(f.low), float(f.high)) for f in space.factors if isinstance(f, Factor)}
    return finish_mixture(design.kind, names, np.repeat(P, len(pts), axis=0), types, design.total, lows, seed=seed,
                   randomize=randomize, options=opts, process=space, process_coded=np.tile(pts, (len(P), 1)))
