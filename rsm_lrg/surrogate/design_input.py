"""Reading and checking a design for virtual runs: a DataFrame in, NumPy columns out.

A design row is one test of the rig (Section 4 of Su, Zhang & Yang 2023). Columns:

``thickness_m``        hinge thickness y [m] (Eq. 1); may be empty on ``rms`` rows
``stroke_m``           stroke s [m]
``velocity_m_s``       top speed v [m/s]
``acceleration_m_s2``  acceleration a [m/s²]
``stage``              optional: ``rfcms`` (default) or ``rms`` (case-insensitive)
any name of :class:`rsm_lrg.physics.params.LRGParams` (``preload_n``, ``mu_k``,
``ambient_c``, ``test_duration_min``, ...) or of the surrogate's calibrated parameters
(``heat_partition``): a per-row value of that parameter.

Every other column passes through untouched. Missing or out-of-range values raise
``ValueError`` naming the column and the (1-based) data row.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["FACTOR_COLUMNS", "STAGES", "DesignArrays", "read_design_arrays", "OUTPUT_COLUMNS",
           "EXTRA_OUTPUT_COLUMNS"]

#: The four factors of the paper's study (Table 3), in order.
FACTOR_COLUMNS = ("thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2")

#: Values of the ``stage`` column.
STAGES = ("rfcms", "rms")

#: Columns the surrogate adds (INTERFACE.md promises the first five).
OUTPUT_COLUMNS = (
    "tcr_c_per_min", "temperature_rise_k", "steady_rise_k", "wear_volume_m3_per_h",
    "sliding_distance_m_per_cycle", "heat_w", "cycle_time_s",
)

#: Further columns the surrogate adds (the leaves' peak stress [Pa] and whether it is above
#: ``hinge_yield_pa``).
EXTRA_OUTPUT_COLUMNS = ("hinge_peak_stress_pa", "hinge_yields")

#: Parameters that are factors of the design, or fixed by the stage, or per-run switches
#: that cannot vary row by row.
_NOT_PER_ROW = {"hinge_thickness_m", "heat_in_calories"}


@dataclass(frozen=True)
class DesignArrays:
    """A checked design as NumPy columns (one entry per row, row order kept).

    Attributes
    ----------
    n : int
        Number of rows.
    columns : dict[str, numpy.ndarray]
        ``thickness_m`` (NaN on ``rms`` rows where empty), ``stroke_m``, ``velocity_m_s``,
        ``acceleration_m_s2`` [SI] and every per-row physical parameter column [SI].
    rigid : numpy.ndarray of bool
        True for ``rms`` rows.
    param_columns : tuple of str
        The physical-parameter columns found in the design.
    """

    n: int
    columns: dict = field(repr=False)
    rigid: np.ndarray = field(repr=False)
    param_columns: tuple = ()

    def take(self, start: int, stop: int) -> DesignArrays:
        """Rows ``start:stop`` as a new :class:`DesignArrays` (views, no copy)."""
        return DesignArrays(stop - start, {k: v[start:stop] for k, v in self.columns.items()},
                            self.rigid[start:stop], self.param_columns)


def _bad_row(col, values, mask, rule: str) -> ValueError:
    from ..io import quote_user_value

    i = int(np.flatnonzero(mask)[0])
    return ValueError(f"column {quote_user_value(col)}, row {i + 1}: {quote_user_value(values[i])} is out of "
                      f"range ({rule})")


def _float_column(df, name: str, allow_empty=None) -> np.ndarray:
    from ..table import is_column_table

    if is_column_table(df):  # numbers already, none empty (a plain CSV file read without pandas)
        num = np.asarray(df[name], dtype=float)
        bad_rows = np.flatnonzero(~np.isfinite(num))
        if bad_rows.size:
            from ..io import quote_user_value

            i = int(bad_rows[0])
            raise ValueError(f"column {name!r}, row {i + 1}: holds {quote_user_value(num[i])}, not a finite number")
        return num
    import pandas as pd

    raw = df[name]
    num = pd.to_numeric(raw, errors="coerce").to_numpy(dtype=float, na_value=np.nan)
    bad = ~np.isfinite(num)
    if pd.api.types.is_bool_dtype(raw.dtype) or raw.dtype == object:  # True is not 1 m/s
        bad |= raw.map(lambda x: isinstance(x, (bool, np.bool_))).to_numpy(dtype=bool)
    if allow_empty is not None:
        empty = raw.isna().to_numpy() | (raw.astype(str).str.strip() == "").to_numpy()
        bad &= ~(empty & allow_empty)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        v = raw.iloc[i]
        if v is None or (isinstance(v, float) and math.isnan(v)) or str(v).strip() == "":
            raise ValueError(f"column {name!r}, row {i + 1}: is empty")
        from ..io import quote_user_value

        raise ValueError(f"column {name!r}, row {i + 1}: holds {quote_user_value(v)}, not a finite number")
    return num


def _check_near_names(cols) -> None:
    """A column whose name differs from one the surrogate reads only in case or surrounding
    spaces (``Stage``, ``Mu_K``, `` stroke_m``) would pass through unused -- a ``Stage``
    column of ``rms`` rows would run them as RFCMS: refuse it, naming the column."""
    from ..physics.params import param_names
    from .runs import SURROGATE_PARAMETERS

    known = {*FACTOR_COLUMNS, "stage", *param_names(), *SURROGATE_PARAMETERS}
    folded = {k.lower(): k for k in known}
    for c in cols:
        if c not in known and c.strip().lower() in folded and folded[c.strip().lower()] not in cols:
            from ..io import quote_user_value

            raise ValueError(f"column {quote_user_value(c)}: the surrogate reads {folded[c.strip().lower()]!r} "
                             f"(names are case-sensitive); rename the column, or it would pass through unused")


def read_design_arrays(df, params=None) -> DesignArrays:
    """Check a design DataFrame and return its columns as arrays.

    Parameters
    ----------
    df : pandas.DataFrame or rsm_lrg.table.ColumnTable
        One row per virtual run (see the module docstring for the columns).
    params : rsm_lrg.physics.params.LRGParams, optional
        Base parameters, for the limits that depend on them (the stroke must fit on the rail).

    Returns
    -------
    DesignArrays
        The checked columns [SI] and the stage of each row.

    Raises
    ------
    ValueError
        A required column is missing, or a value is empty, not a number or out of range;
        the message names the column and the 1-based data row.
    """
    from ..physics.params import (
        LEAF_TOO_THICK,
        OFF_THE_RAIL,
        LRGParams,
        check_values,
        leaf_too_thick,
        off_the_rail,
        param_names,
    )
    from ..table import is_column_table

    if is_column_table(df) and "stage" in df.columns:
        df = df.to_frame()  # a stage column of numbers: refused below as a DataFrame's is, in the same words
    if not is_column_table(df):
        import pandas as pd

        if not isinstance(df, pd.DataFrame):
            raise TypeError(f"the design must be a pandas DataFrame, not {type(df).__name__}")
    if df.shape[0] == 0:
        raise ValueError("the design has no rows")
    p = params if params is not None else LRGParams()
    cols = [str(c) for c in df.columns]
    if len(set(cols)) != len(cols):
        dup = sorted({c for c in cols if cols.count(c) > 1})[0]
        raise ValueError(f"column {dup!r} appears more than once")
    n = int(df.shape[0])
    _check_near_names(cols)

    # stage
    if "stage" in df.columns:
        s = df["stage"]
        empty = s.isna().to_numpy()
        text = s.astype(str).str.strip().str.lower()
        ok = text.isin(STAGES).to_numpy() & ~empty
        if not ok.all():
            i = int(np.flatnonzero(~ok)[0])
            v = s.iloc[i]
            from ..io import quote_user_value

            what = "is empty" if empty[i] or str(v).strip() == "" else f"holds {quote_user_value(v)}"
            raise ValueError(f"column 'stage', row {i + 1}: {what}; expected 'rfcms' or 'rms'")
        rigid = (text == "rms").to_numpy()
    else:
        rigid = np.zeros(n, dtype=bool)

    missing = [c for c in FACTOR_COLUMNS if c not in df.columns and not (c == "thickness_m" and rigid.all())]
    if missing:
        raise ValueError(
            f"the design lacks column {missing[0]!r} (needed: {', '.join(FACTOR_COLUMNS)}; "
            f"found: {', '.join(cols)})")
    if "hinge_thickness_m" in df.columns:
        raise ValueError("column 'hinge_thickness_m': give the hinge thickness as column 'thickness_m'")
    for c in ("heat_in_calories", "hinge_membrane"):  # switches of the physics, one per run
        if c in df.columns:
            raise ValueError(f"column {c!r} cannot vary row by row; set it in the parameters")

    columns: dict[str, np.ndarray] = {}
    if "thickness_m" in df.columns:
        y = _float_column(df, "thickness_m", allow_empty=rigid)
    else:
        y = np.full(n, np.nan)
    for c in FACTOR_COLUMNS[1:]:
        columns[c] = _float_column(df, c)
    columns["thickness_m"] = y

    from .runs import SURROGATE_PARAMETERS

    names = (set(param_names()) - _NOT_PER_ROW) | set(SURROGATE_PARAMETERS)
    param_cols = tuple(c for c in cols if c in names and c not in FACTOR_COLUMNS)
    for c in param_cols:
        columns[c] = _float_column(df, c)
    for c, (rule, is_bad) in {
        "heat_partition": ("must lie in (0, 1]", lambda x: (x <= 0) | (x > 1)),
        "drive_friction_n": ("must lie in [0, 1e4] N", lambda x: ~((x >= 0) & (x <= 1e4))),
        "drive_viscous_n_s_m": ("must lie in [0, 1e4] N s/m", lambda x: ~((x >= 0) & (x <= 1e4))),
    }.items():
        if c in columns and is_bad(columns[c]).any():
            raise _bad_row(c, df[c].tolist(), is_bad(columns[c]), rule)

    # ranges: the physics' own rules, then the rig's limits
    for c, name in (("stroke_m", "stroke_m"), ("velocity_m_s", "velocity_m_s"),
                    ("acceleration_m_s2", "acceleration_m_s2"),
                    *((c, c) for c in param_cols if c not in SURROGATE_PARAMETERS)):
        try:
            check_values(name, columns[c])
        except ValueError as exc:
            msg = str(exc)
            rule = msg.split(" must ", 1)[1].split(", got", 1)[0] if " must " in msg else msg
            bad = np.ones(n, dtype=bool)
            for i in range(n):  # locate the row (only reached on error)
                try:
                    check_values(name, columns[c][i])
                except ValueError:
                    break
                bad[i] = False
            raise _bad_row(c, df[c].tolist(), bad, f"must {rule}") from None
    yv = columns["thickness_m"]
    bad = ~rigid & ~(yv > 0)
    if bad.any():
        raise _bad_row("thickness_m", df["thickness_m"].tolist(), bad, "must be > 0")
    length = columns.get("hinge_length_m", np.full(n, p.hinge_length_m))
    bad = ~rigid & leaf_too_thick(yv, length)
    if bad.any():
        raise _bad_row("thickness_m", df["thickness_m"].tolist(), bad, LEAF_TOO_THICK)
    rail = columns.get("rail_length_m", np.full(n, p.rail_length_m))
    block = columns.get("block_length_m", np.full(n, p.block_length_m))
    bad = off_the_rail(columns["stroke_m"], rail, block)
    if bad.any():
        raise _bad_row("stroke_m", df["stroke_m"].tolist(), bad, OFF_THE_RAIL)
    if "test_duration_min" in columns:
        bad = columns["test_duration_min"] < 1.0
        if bad.any():
            raise _bad_row("test_duration_min", df["test_duration_min"].tolist(), bad,
                           "a test needs at least two readings, one minute apart: >= 1")
    if "frame_mass_fraction" in columns or "stage_mass_kg" in columns:
        pass  # validated by check_values above
    return DesignArrays(n, columns, rigid, param_cols)
