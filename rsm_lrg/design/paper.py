"""The paper's design: Table 4 of Su, Zhang & Yang (2023) as a :class:`Design`.

Table 4 lists 27 runs of a 4-factor Box–Behnken design with 3 centre runs over the Table 3
levels (thickness 0.0001–0.0005 m, stroke 0.04–0.06 m, velocity 0.4–0.6 m/s, acceleration
20–40 m/s²), in the order they were run (column ``order``). :func:`paper_design` matches
each run to the generator's standard order (a check that the paper's runs are, as a
multiset, exactly the published design) and keeps the paper's run order.
"""

from __future__ import annotations

from .box_behnken import box_behnken
from .core import Design

__all__ = ["paper_design", "PAPER_LEVELS"]

#: Table 3 of the paper: factor -> (low, high) [SI units].
PAPER_LEVELS = {
    "thickness_m": (0.0001, 0.0005),
    "stroke_m": (0.04, 0.06),
    "velocity_m_s": (0.4, 0.6),
    "acceleration_m_s2": (20.0, 40.0),
}


def paper_design() -> Design:
    """The paper's 27-run design (Table 4) with its own run order.

    ``std_order`` comes from :func:`~rsm_lrg.design.box_behnken` (4 factors, 3 centre
    runs, unrandomised); ``run_order`` is Table 4's ``order`` column.

    Returns
    -------
    Design
        The 27 runs of Table 4 in the paper's run order.

    Raises
    ------
    ValueError
        If a Table 4 run is not a run of that design (it is not: this is checked).

    >>> d = paper_design()
    >>> d.n_runs, d.run_order[:3].tolist(), d.std_order[:3].tolist()
    (27, [1, 2, 3], [13, 2, 8])
    """
    from ..datasets import load_table4

    t4 = load_table4()
    levels = _table3_levels()
    bbd = box_behnken(levels, center=3, randomize=False)
    d = bbd.with_runs_of(t4, run_order="order")
    opts = dict(d.options)
    opts["source"] = "Su, Zhang & Yang (2023), Machines 11(3):358, Tables 3 and 4"
    return Design(d.factors, d.kind, d.coded_runs, d.std_order, d.run_order, d.blocks, opts)


def _table3_levels() -> dict:
    """Table 3 levels read from the shipped data, in the factor order of Table 4."""
    from ..datasets import load_table3

    t3 = load_table3()
    names = {"A": "thickness_m", "B": "stroke_m", "C": "velocity_m_s", "D": "acceleration_m_s2"}
    out = {}
    for _, row in t3.iterrows():
        out[names[row["letter"]]] = (float(row["low"]), float(row["high"]))
    if out != PAPER_LEVELS:
        raise ValueError("the shipped Table 3 levels differ from PAPER_LEVELS")
    return out
