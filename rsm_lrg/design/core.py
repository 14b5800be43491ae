"""The :class:`Design` object shared by every generator, randomisation, and the CSV layout.

A design is a table of runs over a :class:`~rsm_lrg.factors.FactorSpace`. Each run keeps
its *standard order* (the order in which the generator lists it, ``std_order`` 1..N) and
gets a *run order* (the order in which it is to be run, ``run_order`` 1..N), randomised
from a seed so that the same seed gives the same order. Rows are held in run order.

The CSV layout (what ``rsm-lrg design`` writes and what later commands read)::

    std_order, run_order, [block,] [whole_plot,] coded_A, coded_B, ..., <factor name>, ...

A split-plot design (:func:`rsm_lrg.design.split_plot`) adds the ``whole_plot`` column: the
whole plot (1..W, numbered in run order) of each run; its hard-to-change factors are constant
within each whole plot. A split-split-plot design adds ``subplot`` beside it (sub-plots
numbered 1..S across the design, nested in the whole plots), a strip-plot design ``strip_row``
and ``strip_column`` (:mod:`rsm_lrg.design.multi_stratum`); these group columns stand before
the coded columns, where ``fit --random-effect COL`` reads them.

The coded columns carry the prefix ``coded_`` so that ``fit`` skips them when it picks the
factor columns by default (see :meth:`rsm_lrg.factors.FactorSpace.from_data`).
"""

from __future__ import annotations

import math
import secrets
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError
from ..factors import CategoricFactor, Factor, FactorSpace, letters_for, level_text
from ..factors.columns import BOOKKEEPING, design_factors
from ..factors.spec import given_items
from ..io import float_column, is_empty_cell
from ..present import format_g

__all__ = [
    "Design",
    "read_design",
    "as_factor_space",
    "resolve_seed",
    "seeded_options",
    "design_of_frame",
    "whole_plot_codes",
    "randomized_run_order",
    "CODED_PREFIX",
    "BLOCK_COLUMN",
    "WHOLE_PLOT_COLUMN",
    "STRATUM_COLUMNS",
    "cross_categoric",
    "numeric_part",
    "check_center",
]

#: Prefix of the coded columns in a design CSV (``coded_A``, ``coded_B``, ...).
CODED_PREFIX = "coded_"
#: Name of the block column in a design CSV.
BLOCK_COLUMN = "block"
#: Name of the whole-plot column of a split-plot design CSV.
WHOLE_PLOT_COLUMN = "whole_plot"
#: The further group columns a design CSV may carry (a split-split-plot design's sub-plots,
#: a strip-plot design's row and column strips), in the order they are written.
STRATUM_COLUMNS = ("subplot", "strip_row", "strip_column")

# Relative tolerance when reading the coding back from coded + actual columns.
_READ_RTOL = 1e-9


def as_factor_space(factors: Any) -> FactorSpace:
    """A :class:`FactorSpace` from a FactorSpace, ``{name: (low, high)}``, or specs.

    Parameters
    ----------
    factors : FactorSpace, mapping, or sequence
        A ready :class:`FactorSpace`; a mapping ``{name: (low, high) | [levels]}`` (in
        order; a list or tuple of texts is a categoric factor's levels); or a sequence
        whose items are ``"NAME=LOW:HIGH"`` / ``"NAME=cat:L1,L2,..."`` strings,
        ``(name, low, high)`` tuples or :class:`Factor` / :class:`CategoricFactor`
        objects. Letters go to the numeric factors first, then the categoric ones.

    Returns
    -------
    FactorSpace
        The factors.

    Notes
    -----
    >>> as_factor_space(["x=0:10", "y=1:2"]).names
    ['x', 'y']
    >>> sp = as_factor_space(["stage=cat:rfcms,rms", "v=0.4:0.6"])
    >>> sp.names, sp.letters
    (['v', 'stage'], ['A', 'B'])
    """
    if isinstance(factors, FactorSpace):
        return factors
    if isinstance(factors, (str, bytes)):
        raise TypeError("factors must be a list of 'NAME=LOW:HIGH' strings, not a single string")
    if not isinstance(factors, Mapping):
        try:
            factors = list(factors)
        except TypeError:
            raise TypeError(
                "factors must be a FactorSpace, a mapping {name: (low, high)} or a list of "
                f"'NAME=LOW:HIGH' strings, not {type(factors).__name__}"
            ) from None
    return FactorSpace.from_items(given_items(factors, need_levels=True))


def numeric_part(space: FactorSpace) -> tuple[FactorSpace, int]:
    """The numeric factors as a space of their own (letters A, B, ... as in ``space``, since
    numeric factors take the first letters) and their number.

    Raises ``ValueError`` when the categoric factors do not follow the numeric ones (a
    space built by :func:`as_factor_space` always has them last).
    """
    kn = len(space.numeric)
    if space.numeric_index != list(range(kn)):
        raise ValueError("the numeric factors must come first (letters A, B, ...), the categoric ones after")
    return FactorSpace(tuple(space.factors[:kn])), kn


def cross_categoric(space: FactorSpace, coded_numeric: np.ndarray,
                    blocks: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray | None]:
    """Cross a numeric design with every combination of the categoric levels.

    The numeric runs (standard order) are repeated once per combination of levels (the
    first categoric factor's level changing slowest), Design-Expert's layout: centre points
    are then per combination. A categoric factor's coded value is its level index. Blocks
    of the numeric design are kept (each block holds every combination).

    Returns the coded runs ``(n * combinations, k)`` and the blocks (or ``None``).
    """
    coded_numeric = np.asarray(coded_numeric, dtype=float)
    cats = [f for f in space.factors if f.kind == "categoric"]
    if not cats:
        return coded_numeric, blocks
    import itertools

    combos = list(itertools.product(*[range(f.n_levels) for f in cats]))
    n = coded_numeric.shape[0]
    parts = [np.hstack([coded_numeric, np.tile(np.asarray(c, dtype=float), (n, 1))]) for c in combos]
    b = None if blocks is None else np.tile(np.asarray(blocks, dtype=int), len(combos))
    return np.vstack(parts), b


def resolve_seed(seed: Any) -> tuple[np.random.Generator, int | None]:
    """A NumPy generator for ``seed`` and the integer seed to record (if there is one).

    ``None`` draws a fresh 32-bit seed (from :mod:`secrets`) and returns it, so that a
    design made without a seed can still be reproduced from the seed it records.
    """
    if isinstance(seed, np.random.Generator):
        return seed, None
    if seed is None:
        seed = secrets.randbits(32)
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise TypeError(f"seed must be an integer or a numpy.random.Generator, not {type(seed).__name__}")
    if seed < 0:
        raise ParameterError("seed", f"seed must not be negative (got {seed})")
    return np.random.default_rng(int(seed)), int(seed)


def seeded_options(options: Any, seed: Any, randomize: bool) -> tuple[np.random.Generator | None, dict]:
    """The generator of a randomised run order (None with ``randomize=False``) and a copy of
    a design's ``options`` recording ``seed`` (the one drawn when None) and ``randomize``."""
    opts = dict(options or {})
    rng, used = resolve_seed(seed) if randomize else (None, None)
    opts["seed"] = used
    opts["randomize"] = bool(randomize)
    return rng, opts


def randomized_run_order(blocks: np.ndarray | None, n: int, rng: np.random.Generator | None) -> np.ndarray:
    """Run order (1..n) for runs given in standard order.

    With ``rng=None`` the run order is the standard order. Otherwise runs are shuffled,
    within each block when ``blocks`` is given (blocks keep their order: all of block 1
    runs first, then block 2, ...), as R ``rsm``'s ``bbd``/``ccd`` randomise.

    Returns
    -------
    numpy.ndarray
        ``perm`` such that ``perm[j]`` is the 0-based standard-order index of the run made
        ``j``-th.
    """
    idx = np.arange(n)
    if rng is None:
        if blocks is not None:
            return idx[np.argsort(blocks, kind="stable")]
        return idx
    if blocks is None:
        return rng.permutation(n)
    out = []
    for b in sorted(set(blocks.tolist())):
        members = idx[blocks == b]
        out.append(members[rng.permutation(len(members))])
    return np.concatenate(out)


def _clean_actual(f: Factor, coded: np.ndarray) -> np.ndarray:
    """Decode, keeping low/high exact and trimming float noise off the other levels.

    ``(0.0001 + 0.0005) / 2`` is ``0.00030000000000000003`` in binary floating point; a
    design CSV should say ``0.0003``. A value is rounded to the fewest significant digits
    (12 to 16) whose rounded value still codes to the same coded value (coded values are
    themselves kept to 12 decimals, see :mod:`rsm_lrg.factors`): ``-0.2071067811865``, not
    ``-0.20710678118650006``; otherwise the neighbouring float that codes back exactly is
    taken when there is one. When the range is very narrow
    compared with the levels (e.g. 128 to 128.001) no float may code back exactly; the
    round trip is then exact only to float resolution, about
    ``eps * max(|low|, |high|) / half_range`` in coded units.
    """
    x = np.asarray(f.decode(coded), dtype=float)
    out = x.copy()
    for i, (c, v) in enumerate(zip(np.asarray(coded, dtype=float), x)):
        if c in (-1.0, 1.0):
            continue
        target = f.encode(v) if f.encode(v) == c else c
        cands = [float(f"{v:.{digits}g}") for digits in range(12, 17)] + [v]  # the shortest that codes back
        cands += [float(np.nextafter(v, d * np.inf)) for d in (-1, 1)]
        for cand in cands:
            if f.encode(cand) == target:
                out[i] = cand
                break
    return out


@dataclass(frozen=True, eq=False)
class Design:
    """An experimental design: factor space, generator, options and the run table.

    Rows are in run order. Build one with a generator (:func:`~rsm_lrg.design.box_behnken`,
    :func:`~rsm_lrg.design.central_composite`, :func:`~rsm_lrg.design.full_factorial`) or
    read one back with :func:`read_design` / :meth:`Design.from_frame`.

    Attributes
    ----------
    factors : FactorSpace
        The factors, their low/high levels (coded -1/+1) and letters.
    kind : str
        ``"box-behnken"``, ``"central-composite"``, ``"full-factorial"`` or ``"custom"``
        (read from a file).
    coded_runs : numpy.ndarray, shape (n, k)
        Coded settings [-], rows in run order, columns in factor order.
    std_order : numpy.ndarray of int, shape (n,)
        Standard order (1..n) of each row.
    run_order : numpy.ndarray of int, shape (n,)
        Run order (1..n) of each row; increasing, since rows are held in run order.
    blocks : numpy.ndarray of int or None
        Block (1..b) of each row, or ``None`` for an unblocked design.
    options : dict
        The generator's options (centre points, alpha, seed, ...), JSON-safe.
    whole_plots : numpy.ndarray of int or None
        Whole plot (1..W) of each row of a split-plot design, or ``None``.
    strata : dict
        Further group columns (names among :data:`STRATUM_COLUMNS`) to their group numbers
        (>= 1) per row: ``subplot`` of a split-split-plot design, ``strip_row`` and
        ``strip_column`` of a strip-plot design; empty for other designs.
    """

    factors: FactorSpace
    kind: str
    coded_runs: np.ndarray
    std_order: np.ndarray
    run_order: np.ndarray
    blocks: np.ndarray | None = None
    options: dict = field(default_factory=dict)
    whole_plots: np.ndarray | None = None
    strata: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        coded = np.array(self.coded_runs, dtype=float)
        k = len(self.factors)
        if coded.ndim != 2 or coded.shape[1] != k:
            raise ValueError(f"coded runs must be an (n, {k}) array, got shape {coded.shape}")
        n = coded.shape[0]
        if n == 0:
            raise ValueError("a design needs at least one run")
        if not np.all(np.isfinite(coded)):
            raise ValueError("coded runs must be finite numbers")
        std = np.asarray(self.std_order, dtype=int)
        run = np.asarray(self.run_order, dtype=int)
        for name, arr in (("std_order", std), ("run_order", run)):
            if arr.shape != (n,) or sorted(arr.tolist()) != list(range(1, n + 1)):
                raise ValueError(f"{name} must hold each of 1..{n} exactly once")
        blocks = None
        if self.blocks is not None:
            blocks = np.asarray(self.blocks, dtype=int)
            if blocks.shape != (n,) or blocks.min() < 1:
                raise ValueError("blocks must give a block number >= 1 for every run")
        plots = None
        if self.whole_plots is not None:
            plots = np.asarray(self.whole_plots, dtype=int)
            if plots.shape != (n,) or plots.min() < 1:
                raise ValueError("whole_plots must give a whole plot number >= 1 for every run")
        order = np.argsort(run, kind="stable")
        coded = np.round(coded[order], 12) + 0.0
        std, run = std[order], run[order]
        blocks = None if blocks is None else blocks[order]
        plots = None if plots is None else plots[order]
        strata: dict[str, np.ndarray] = {}
        for name, labels in dict(self.strata or {}).items():
            if name not in STRATUM_COLUMNS:
                raise ValueError(f"strata: {name!r} is not one of {', '.join(STRATUM_COLUMNS)}")
            g = np.asarray(labels, dtype=int)
            if g.shape != (n,) or g.min() < 1:
                raise ValueError(f"strata: {name} must give a group number >= 1 for every run")
            strata[name] = g[order]
        for a in (coded, std, run) + tuple(x for x in (blocks, plots) if x is not None) + tuple(strata.values()):
            a.setflags(write=False)
        object.__setattr__(self, "coded_runs", coded)
        object.__setattr__(self, "std_order", std)
        object.__setattr__(self, "run_order", run)
        object.__setattr__(self, "blocks", blocks)
        object.__setattr__(self, "whole_plots", plots)
        object.__setattr__(self, "strata", {c: strata[c] for c in STRATUM_COLUMNS if c in strata})
        object.__setattr__(self, "options", dict(self.options))

    # -- sizes ----------------------------------------------------------------------------
    @property
    def n_runs(self) -> int:
        """Number of runs."""
        return int(self.coded_runs.shape[0])

    @property
    def n_factors(self) -> int:
        """The number of factors."""
        return len(self.factors)

    @property
    def n_blocks(self) -> int:
        """Number of blocks (1 for an unblocked design)."""
        return 1 if self.blocks is None else int(len(set(self.blocks.tolist())))

    @property
    def n_center(self) -> int:
        """Number of centre runs (every numeric factor's coded value 0; with categoric
        factors, centre runs of every level combination count)."""
        idx = self.factors.numeric_index
        return int(np.sum(np.all(self.coded_runs[:, idx] == 0.0, axis=1)))

    def __len__(self) -> int:
        return self.n_runs

    # -- views ----------------------------------------------------------------------------
    @property
    def coded(self):
        """Coded settings [-] as a DataFrame keyed by letter (``A``, ``B``, ...), in run order."""
        import pandas as pd

        return pd.DataFrame(self.coded_runs.copy(), columns=self.factors.letters)

    @property
    def actual(self):
        """Actual settings [factor units] as a DataFrame keyed by factor name, in run order."""
        import pandas as pd

        return pd.DataFrame(
            {f.name: (_clean_actual(f, self.coded_runs[:, i]) if f.kind == "numeric"
                      else f.decode(self.coded_runs[:, i])) for i, f in enumerate(self.factors)}
        )

    def to_frame(self):
        """The design CSV layout as a DataFrame (rows in run order).

        Columns: ``std_order``, ``run_order``, ``block`` (only when blocked), ``whole_plot``
        (only for a split-plot design), ``coded_A``, ``coded_B``, ... and then the actual
        columns named after the factors.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        cols: dict[str, Any] = {"std_order": self.std_order.copy(), "run_order": self.run_order.copy()}
        if self.blocks is not None:
            cols[BLOCK_COLUMN] = self.blocks.copy()
        if self.whole_plots is not None:
            cols[WHOLE_PLOT_COLUMN] = self.whole_plots.copy()
        for name, g in self.strata.items():
            cols[name] = g.copy()
        for i, f in enumerate(self.factors):
            c = self.coded_runs[:, i]
            if f.kind == "categoric":  # Design-Expert shows the level as the coded value
                cols[CODED_PREFIX + f.letter] = f.decode(c)
                continue
            cols[CODED_PREFIX + f.letter] = c.astype(int) if np.all(c == np.round(c)) else c.copy()
        actual = self.actual
        for f in self.factors:
            cols[f.name] = actual[f.name].to_numpy()
        return pd.DataFrame(cols)

    def check_finite(self) -> None:
        """ValueError naming the factor and the run when a coded or actual value of a numeric
        factor is not finite or is beyond a 64-bit whole number: no design file holds an
        overflowed number (issue 26; the CLI refuses the options that would cause one)."""
        for i, f in enumerate(self.factors):
            if f.kind != "numeric":
                continue
            c = self.coded_runs[:, i].astype(float)
            with np.errstate(all="ignore"):
                a = np.asarray(_clean_actual(f, c), dtype=float)
            bad = ~np.isfinite(c) | ~np.isfinite(a) | (np.abs(c) >= 2.0**63)
            if bad.any():
                j = int(np.flatnonzero(bad)[0])
                raise ValueError(f"the design holds an overflowed number for factor {f.name!r} in run {j + 1} "
                                 f"(coded {c[j]:g}, actual {a[j]:g}); nothing was written")

    def csv_text(self) -> str:
        """The design CSV (:meth:`to_csv`'s text) written without pandas: the same bytes as
        ``to_frame().to_csv(index=False)`` (numbers as their shortest round-trip text, text
        quoted where the CSV dialect needs it), so that ``rsm-lrg design`` does not load
        pandas (about 0.3 s of CPU time at start-up).

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
        if self.whole_plots is not None:
            columns[WHOLE_PLOT_COLUMN] = [str(v) for v in self.whole_plots.tolist()]
        for name, g in self.strata.items():
            columns[name] = [str(v) for v in g.tolist()]

        def text(values: np.ndarray) -> list[str]:
            if values.dtype.kind in "iu":
                return [str(int(v)) for v in values]
            if values.dtype.kind == "f":
                return ["" if math.isnan(v) else repr(float(v)) for v in values.tolist()]
            return ["" if v is None else str(v) for v in values.tolist()]

        for i, f in enumerate(self.factors):
            c = self.coded_runs[:, i]
            if f.kind == "categoric":
                columns[CODED_PREFIX + f.letter] = text(np.asarray(f.decode(c), dtype=object))
            else:
                columns[CODED_PREFIX + f.letter] = text(c.astype(int) if np.all(c == np.round(c)) else c)
        for i, f in enumerate(self.factors):
            c = self.coded_runs[:, i]
            values = _clean_actual(f, c) if f.kind == "numeric" else np.asarray(f.decode(c), dtype=object)
            columns[f.name] = text(np.asarray(values))
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(list(columns))
        w.writerows(zip(*columns.values()))
        return buf.getvalue()

    def standard_order(self):
        """:meth:`to_frame` sorted by ``std_order``.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        return self.to_frame().sort_values("std_order", kind="stable").reset_index(drop=True)

    def to_csv(self, path, force: bool = False):
        """Write the design CSV atomically (see :func:`rsm_lrg.io.write_output`).

        An existing file is kept (``InputError``) unless ``force=True``.

        Parameters
        ----------
        path : str or pathlib.Path
            Where to write the CSV.
        force : bool, default False
            Replace an existing file.

        Returns
        -------
        pathlib.Path
            The path written.
        """
        from ..io import write_output

        self.check_finite()
        return write_output(path, self.csv_text(), force=force)

    def to_dict(self) -> dict:
        """Plain, JSON-safe summary: kind, factors, options and the runs (run order).

        Returns
        -------
        dict
            Plain JSON-safe data (numbers, strings, lists and dicts).
        """
        from ..io import to_jsonable

        return to_jsonable(
            {
                "kind": self.kind,
                "n_runs": self.n_runs,
                "n_blocks": self.n_blocks,
                "n_center": self.n_center,
                "factors": self.factors.to_list(),
                "options": self.options,
                "runs": self.to_frame().to_dict(orient="records"),
            }
        )

    def summary(self) -> str:
        """A few lines for people: kind, factors, runs, blocks, seed.

        Returns
        -------
        str
            Text for people, several lines.
        """
        seed = self.options.get("seed")
        rnd = self.options.get("randomize", True)
        lines = [
            f"{self.kind} design: {self.n_factors} factor{'s' if self.n_factors != 1 else ''}, "
            f"{self.n_runs} run{'s' if self.n_runs != 1 else ''} "
            f"({self.n_runs - self.n_center} non-centre + {self.n_center} centre), "
            f"{self.n_blocks} block{'s' if self.n_blocks != 1 else ''}",
        ]
        if self.kind == "central-composite" and "alpha" in self.options:
            lines.append(f"alpha {format_g(self.options['alpha'], 6, trim=True)} ({self.options.get('alpha_rule')}), "
                         f"face {self.options.get('face')}")
        o = self.options
        if self.kind == "optimal":
            lines.append(f"{o.get('criterion')}-optimal for the {o.get('model')} model ({o.get('model_terms')} terms): "
                         f"criterion {format_g(o.get('criterion_value'), 6, trim=True) or 'n/a'}; {o.get('model_points')} model points, "
                         f"{o.get('replicates')} replicates, {o.get('lof_points')} lack-of-fit points")
        if self.kind == "split-plot":
            lines.append(f"{o.get('criterion')}-optimal split-plot design for the {o.get('model')} model "
                         f"({o.get('model_terms')} terms) under variance ratio eta = "
                         f"{format_g(o.get('variance_ratio'), 6, trim=True)}: GLS criterion "
                         f"{format_g(o.get('criterion_value'), 6, trim=True) or 'n/a'}; hard to change: "
                         + ", ".join(o.get("hard_to_change", [])))
        if self.kind == "split-plot-ccd":
            lines.append(f"equivalent estimation (OLS = GLS for every variance ratio): star distance "
                         f"{format_g(o.get('alpha_whole_plot'), 6, trim=True)} whole plot, "
                         f"{format_g(o.get('alpha_sub_plot'), 6, trim=True)} sub-plot [coded]; hard to change: "
                         + ", ".join(o.get("hard_to_change", [])))
        if self.whole_plots is not None:
            sizes = np.unique(self.whole_plots, return_counts=True)[1]
            each = (f"{int(sizes[0])} runs each" if sizes.min() == sizes.max()
                    else f"{int(sizes.min())} to {int(sizes.max())} runs")
            lines.append(f"{len(sizes)} whole plots ({each})")
        for name, g in self.strata.items():
            sizes = np.unique(g, return_counts=True)[1]
            each = (f"{int(sizes[0])} runs each" if sizes.min() == sizes.max()
                    else f"{int(sizes.min())} to {int(sizes.max())} runs")
            lines.append(f"{len(sizes)} groups in column {name} ({each})")
        if self.kind in ("split-split-plot", "strip-plot"):
            lines.append(f"{o.get('criterion')}-optimal {self.kind} design for the {o.get('model')} model "
                         f"({o.get('model_terms')} terms), variance ratios "
                         + ", ".join(f"{k} {format_g(v, 6, trim=True)}" for k, v in o.get("variance_ratios", {}).items())
                         + f": GLS criterion {format_g(o.get('criterion_value'), 6, trim=True) or 'n/a'}")
            for key, label in (("very_hard_to_change", "very hard to change (whole plots)"),
                               ("hard_to_change", "hard to change (sub-plots)"),
                               ("row_factors", "row factors (strip_row)"),
                               ("column_factors", "column factors (strip_column)")):
                if o.get(key):
                    lines.append(f"{label}: " + ", ".join(o[key]))
        if o.get("constraints"):
            lines.append("constraints: " + "; ".join(o["constraints"]))
        if self.kind == "augmented":
            lines.append(f"augmented: {o.get('original_runs')} original runs kept (std_order 1..{o.get('original_runs')}), "
                         f"{self.n_runs - o.get('original_runs', 0)} added ({o.get('method')})")
        if o.get("note"):
            lines.append(str(o["note"]))
        if not rnd:
            lines.append("run order: standard order (not randomised)")
        elif seed is not None:
            where = (" between and within whole plots (whole plots kept together)" if self.whole_plots is not None
                     else " within blocks" if self.blocks is not None else "")
            lines.append(f"run order: randomised{where}, seed {seed}")
        else:
            lines.append("run order: randomised from a numpy Generator")
        for f in self.factors:
            if f.kind == "categoric":
                lines.append(f"  {f.letter} {f.name}: categoric, levels {', '.join(f.levels)}")
            else:
                lines.append(f"  {f.letter} {f.name}: {format_g(f.low, 6, trim=True)} .. {format_g(f.high, 6, trim=True)}")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return (f"Design(kind={self.kind!r}, factors={self.factors.names!r}, n_runs={self.n_runs}, "
                f"n_blocks={self.n_blocks})")

    # -- construction helpers -------------------------------------------------------------
    @classmethod
    def from_standard(
        cls,
        factors: FactorSpace,
        kind: str,
        coded_std: np.ndarray,
        *,
        blocks_std: np.ndarray | None = None,
        seed: Any = None,
        randomize: bool = True,
        options: Mapping | None = None,
    ) -> Design:
        """Build from runs listed in standard order: assign ``std_order`` and a run order.

        Parameters
        ----------
        coded_std : array, shape (n, k)
            Coded runs in standard order.
        blocks_std : array of int or None
            Block of each standard-order run.
        seed : int, numpy.random.Generator or None
            Randomisation seed (ignored when ``randomize`` is false).
        randomize : bool
            ``False``: run order = standard order (block by block when blocked).

        Returns
        -------
        Design
            The design with ``std_order`` and a (seeded) run order.
        """
        coded_std = np.asarray(coded_std, dtype=float)
        n = coded_std.shape[0]
        rng, opts = seeded_options(options, seed, randomize)
        bstd = None if blocks_std is None else np.asarray(blocks_std, dtype=int)
        perm = randomized_run_order(bstd, n, rng)
        run_order = np.empty(n, dtype=int)
        run_order[perm] = np.arange(1, n + 1)
        return cls(
            factors=factors,
            kind=kind,
            coded_runs=coded_std,
            std_order=np.arange(1, n + 1),
            run_order=run_order,
            blocks=bstd,
            options=opts,
        )

    def with_runs_of(self, data, run_order: str | None = None) -> Design:
        """Match the runs of ``data`` to this design's runs and adopt ``data``'s order.

        Each row of ``data`` (actual settings in the factor columns) is matched to a run of
        this design with the same coded settings (as a multiset: replicated settings such as
        centre runs are matched in standard order). The result keeps this design's
        ``std_order`` for each matched run and takes the run order from the column
        ``run_order`` of ``data`` (or the row order when ``None``).

        Parameters
        ----------
        data : pandas.DataFrame
            Runs with the factor columns in actual units.
        run_order : str, optional
            A column of ``data`` holding the order the runs were made in.

        Returns
        -------
        Design
            This design's runs, in ``data``'s order.

        Raises
        ------
        ValueError
            If the settings of ``data`` are not the same multiset as this design's (the
            message names the first row with no partner).
        """
        if len(data) != self.n_runs:
            raise ValueError(f"the data have {len(data)} runs but the design has {self.n_runs}")
        coded = self.factors.encode(data[self.factors.names]).to_numpy(dtype=float)
        std_sorted = np.argsort(self.std_order, kind="stable")
        pool: dict[tuple, list[int]] = {}
        for i in std_sorted:
            pool.setdefault(tuple(self.coded_runs[i]), []).append(i)
        std = np.empty(len(data), dtype=int)
        given = self.blocks
        blocks = None if given is None else np.empty(len(data), dtype=int)
        for r, row in enumerate(coded):
            key = tuple(np.round(row, 12) + 0.0)
            if not pool.get(key):
                setting = ", ".join(f"{f.name}={level_text(v)}" for f, v in
                                    zip(self.factors, data[self.factors.names].iloc[r]))
                raise ValueError(f"row {r + 1} ({setting}) is not a run of the {self.kind} design (or is one too many)")
            i = pool[key].pop(0)
            std[r] = self.std_order[i]
            if blocks is not None and given is not None:
                blocks[r] = given[i]
        if run_order is None:
            ro = np.arange(1, len(data) + 1)
        else:
            ro = float_column(data, run_order).to_numpy()
            if not np.all(ro == np.round(ro)):
                raise ValueError(f"column {run_order!r} must hold whole numbers")
            ro = ro.astype(int)
        opts = dict(self.options)
        opts.update(seed=None, randomize=False, run_order_from="data")
        return Design(self.factors, self.kind, coded, std, ro, blocks, opts)

    @classmethod
    def from_frame(cls, df, *, kind: str = "custom", whole_plot: str | None = None) -> Design:
        """Read a design back from its CSV layout (see :meth:`to_frame`).

        The factors are the columns that follow the coded columns, one per coded column
        (``coded_A`` pairs with the first, ``coded_B`` with the second, ...). Each factor's
        low and high levels are recovered from the coded/actual pairs (actual = centre +
        half-range × coded), which must agree on every row to 1e-9 relative. When they do
        not (the actual columns were moved), each coded column is paired with the numeric
        column that is a rising linear map of it, as :func:`rsm_lrg.factors.choose_factors`
        pairs them for a fit. Columns after the actual ones (responses added by
        ``simulate``, say) are ignored here.
        ``std_order``/``run_order`` default to the row order when absent. The whole plots
        of a split-plot design come from the column ``whole_plot`` (or the column named by
        ``whole_plot``): whole numbers >= 1 are kept, other labels numbered 1, 2, ... in order
        of first appearance.

        Parameters
        ----------
        df : pandas.DataFrame
            The design CSV layout.
        kind : str, default "custom"
            The design's kind, as recorded.
        whole_plot : str, optional
            The whole-plot column of a split-plot design.

        Returns
        -------
        Design
            The design read back.
        """
        cols = [str(c) for c in df.columns]
        coded_cols = [c for c in cols if c.lower().startswith(CODED_PREFIX)]
        if not coded_cols:
            raise ValueError(
                "no coded columns (coded_A, coded_B, ...) found; a design CSV carries the coded "
                "columns followed by the actual factor columns"
            )
        last = max(cols.index(c) for c in coded_cols)
        first = min(cols.index(c) for c in coded_cols)
        if cols[first:last + 1] != coded_cols:
            raise ValueError("the coded columns (coded_A, coded_B, ...) must stand next to each other")
        k = len(coded_cols)
        wp_col = whole_plot if whole_plot is not None else (WHOLE_PLOT_COLUMN if WHOLE_PLOT_COLUMN in cols else None)
        if wp_col is not None and wp_col not in cols:
            raise ValueError(f"whole-plot column {wp_col!r} not found (columns: {', '.join(cols)})")
        group_cols = [c for c in STRATUM_COLUMNS if c in cols]
        after = [c for c in cols[last + 1:]
                 if c.lower() not in BOOKKEEPING and c not in (BLOCK_COLUMN, wp_col, *group_cols)]
        if len(after) < k:
            raise ValueError(
                f"found {k} coded columns but only {len(after)} factor columns after them; "
                "each coded column needs its actual column"
            )
        names = after[:k]
        letters = letters_for(k)
        for L, cc in zip(letters, coded_cols):
            expect = CODED_PREFIX + L
            if cc != expect:
                raise ValueError(f"coded column {cc!r} found where {expect!r} was expected")
        import pandas as pd

        std_rank = None
        if "std_order" in cols and pd.api.types.is_numeric_dtype(df["std_order"]):
            std_rank = np.argsort(df["std_order"].to_numpy(), kind="stable")
        built: list[Factor | CategoricFactor]
        try:
            built = []
            for L, cc, name in zip(letters, coded_cols, names):
                if _is_text_column(df[cc]):
                    built.append(_categoric_pair(df, cc, name, L, std_rank))
                else:
                    lo_hi = _levels_from_pairs(float_column(df, cc).to_numpy(), float_column(df, name).to_numpy(), cc, name)
                    built.append(Factor(name, *lo_hi, L))
        except ValueError as exc:
            # the actual columns moved (or others put between them): pair by values, as fit
            # does (rsm_lrg.factors.choose_factors), or report the positional problem
            try:
                found, _ = design_factors(df, coded_cols, set())
            except ValueError:
                raise exc from None
            built = []
            for L, item in zip(letters, found):
                if len(item) == 2:
                    built.append(CategoricFactor(item[0], item[1], L))
                else:
                    float_column(df, item[0])
                    built.append(Factor(item[0], item[1], item[2], L))
        space = FactorSpace(tuple(built))
        coded_all = []
        for f, cc in zip(built, coded_cols):
            if f.kind == "categoric":
                coded_all.append(f.encode(df[f.name].to_numpy(dtype=object)))
            else:
                coded_all.append(float_column(df, cc).to_numpy())
        coded = np.column_stack(coded_all)
        n = len(df)

        def _order(col):
            if col not in cols:
                return np.arange(1, n + 1)
            v = float_column(df, col).to_numpy()
            if not np.all(v == np.round(v)):
                raise ValueError(f"column {col!r} must hold whole numbers")
            return v.astype(int)

        blocks = None
        if BLOCK_COLUMN in cols:
            b = df[BLOCK_COLUMN]
            codes = {v: i + 1 for i, v in enumerate(sorted(set(b.tolist()), key=lambda v: (str(type(v)), v)))}
            blocks = np.array([codes[v] for v in b.tolist()], dtype=int)
        plots = None if wp_col is None else whole_plot_codes(df[wp_col].tolist(), wp_col)
        strata = {c: whole_plot_codes(df[c].tolist(), c) for c in group_cols}
        return cls(space, kind, coded, _order("std_order"), _order("run_order"), blocks,
                   {"source": "file"}, plots, strata)


def whole_plot_codes(values: list, column: str) -> np.ndarray:
    """Whole-plot numbers of a column's cells: whole numbers >= 1 as they are, any other
    labels numbered 1, 2, ... in order of first appearance; an empty cell is a ValueError
    naming the column and the row."""
    for i, v in enumerate(values):
        if is_empty_cell(v):
            raise ValueError(f"whole-plot column {column!r}, row {i + 1}: is empty")
    try:
        nums = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        nums = None
    if nums is not None and np.all(np.isfinite(nums)) and np.all(nums == np.round(nums)) and nums.min() >= 1 \
            and nums.max() < 2.0 ** 62:
        return nums.astype(np.int64)
    codes: dict = {}
    return np.array([codes.setdefault(level_text(v), len(codes) + 1) for v in values], dtype=np.int64)


def _is_text_column(col) -> bool:
    import pandas as pd

    return not pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col)


def _categoric_pair(df, ccol: str, xcol: str, letter: str, std_rank) -> CategoricFactor:
    """A categoric factor from its coded column (the level as text) and its actual column
    (the same text on every row); levels in order of first appearance in standard order."""
    c = [None if is_empty_cell(v) else level_text(v) for v in df[ccol].tolist()]
    x = [None if is_empty_cell(v) else level_text(v) for v in df[xcol].tolist()]
    for i, (u, v) in enumerate(zip(c, x)):
        if u is None or v is None:
            raise ValueError(f"row {i + 1}: {ccol if u is None else xcol} is empty")
        if u != v:
            raise ValueError(f"row {i + 1}: {xcol}={v!r} does not match {ccol}={u!r} (a categoric factor's "
                             "coded column holds its level)")
    order = range(len(c)) if std_rank is None else std_rank
    levels: list = []
    for i in order:
        if c[i] not in levels:
            levels.append(c[i])
    if len(levels) < 2:
        raise ValueError(f"column {ccol!r} holds a single level; a factor needs at least two")
    return CategoricFactor(xcol, tuple(levels), letter)


def _levels_from_pairs(c: np.ndarray, x: np.ndarray, ccol: str, xcol: str) -> tuple[float, float]:
    """Low/high levels from coded values ``c`` and actual values ``x`` (x = m + h c)."""
    uniq = np.unique(c)
    if len(uniq) < 2:
        raise ValueError(f"column {ccol!r} holds a single level; a factor needs at least two")
    at_lo, at_hi = x[c == -1.0], x[c == 1.0]
    if at_lo.size and at_hi.size:
        # the most common actual value at coded -1 and +1 fixes the coding
        low, high = _mode(at_lo), _mode(at_hi)
        m, h = (low + high) / 2.0, (high - low) / 2.0
    else:
        A = np.column_stack([np.ones_like(c), c])
        (m, h), *_ = np.linalg.lstsq(A, x, rcond=None)
        low, high = _tidy(m - h), _tidy(m + h)
    if not h > 0:
        raise ValueError(f"columns {ccol!r} and {xcol!r} do not increase together; they are not a coding pair")
    scale = max(abs(m) + abs(h), float(np.max(np.abs(x))), 1e-300)
    resid = np.abs(x - (m + h * c))
    bad = np.flatnonzero(resid > _READ_RTOL * scale)
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"row {i + 1}: {xcol}={x[i]:g} does not match {ccol}={c[i]:g} under the coding "
            f"of the other rows (low {low:g}, high {high:g})"
        )
    return float(low), float(high)


def _mode(v: np.ndarray) -> float:
    vals, counts = np.unique(v, return_counts=True)
    return float(vals[np.argmax(counts)])


def _tidy(v: float) -> float:
    r = float(f"{v:.12g}")
    return r if math.isclose(r, v, rel_tol=1e-11, abs_tol=0.0) else v


def read_design(path) -> Design:
    """Read a design CSV written by ``rsm-lrg design`` (or :meth:`Design.to_csv`).

    Errors name the file (:class:`rsm_lrg.io.InputError`).

    Parameters
    ----------
    path : str or pathlib.Path
        The design CSV.

    Returns
    -------
    Design
        The design, with its factors, coding, blocks and run order as written.
    """
    from ..io import read_table

    return design_of_frame(read_table(path), path)


def design_of_frame(df: Any, path: Any, whole_plot: str | None = None) -> Design:
    """:meth:`Design.from_frame` of a table read from ``path``, its errors naming the file
    (:class:`rsm_lrg.io.InputError`); ``whole_plot`` names the whole-plot column of a
    split-plot design (default ``whole_plot`` when there is one)."""
    from ..io import InputError

    try:
        return Design.from_frame(df, whole_plot=whole_plot)
    except InputError:
        raise
    except ValueError as exc:
        raise InputError(f"{path}: {exc}") from None


def check_center(center: Any) -> int:
    """``center`` as a number of centre runs (a whole number >= 0), or a TypeError/ValueError."""
    if isinstance(center, (bool, np.bool_)):
        raise TypeError("center must be a whole number of centre runs")
    try:
        c = int(center)
    except (TypeError, ValueError):
        raise TypeError(f"center must be a whole number of centre runs, not {center!r}") from None
    if c != center:
        raise ParameterError("center", f"center must be a whole number of centre runs (got {center!r})")
    if c < 0:
        raise ParameterError("center", f"the number of centre points must not be negative (got {c})")
    return c
