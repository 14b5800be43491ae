"""The paper's published data (and a published mixture example), shipped inside the package.

The files live in ``rsm_lrg/data/`` (package data) and, for people reading the repository,
in ``data/`` at the top level; ``tests/test_datasets.py`` keeps the two identical.
Sources are listed in ``data/README.md``.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["data_path", "load_table4", "load_table3", "load_table5", "load_equation19", "load_mixture_etch"]


def data_path(name: str) -> Path:
    """Filesystem path of a shipped data file (``"table4.csv"``, ``"lrg_shs15v.toml"``, ...)."""
    from importlib import resources  # here, not at import: it costs ~15 ms and most commands never need it

    ref = resources.files("rsm_lrg") / "data" / name
    with resources.as_file(ref) as p:
        if not Path(p).exists():
            raise FileNotFoundError(f"rsm_lrg ships no data file {name!r}")
        return Path(p)


def _csv(name: str):
    import pandas as pd

    return pd.read_csv(data_path(name))


def load_table4():
    """Table 4 of the paper: the 27 Box-Behnken runs and the measured TCR κ [°C/min].

    >>> load_table4().shape
    (27, 6)
    """
    return _csv("table4.csv")


def load_table3():
    """Table 3: factor letters, names, units and the low/centre/high levels."""
    return _csv("table3_levels.csv")


def load_table5():
    """Table 5: the paper's ANOVA as printed (p values kept as text, e.g. ``<0.0001``)."""
    import pandas as pd

    return pd.read_csv(data_path("table5_anova.csv"), dtype={"p_value": str})


def load_equation19():
    """Eq. 19: the coded quadratic coefficients of κ, as a Series indexed by term."""
    return _csv("equation19_coded.csv").set_index("term")["coefficient"]


def load_mixture_etch():
    """A published mixture experiment: the plasma etch rate (``erate``) of 14 blends of three
    components ``x1``, ``x2``, ``x3`` (a simplex-centroid design with the three axial check
    blends, vertices and centroid replicated). Myers & Montgomery, *Response Surface
    Methodology*, 2nd ed. (2002), Table 12.4, as shipped in R mixexp's ``etch`` data set.

    >>> load_mixture_etch().shape
    (14, 4)
    """
    return _csv("mixture_etch.csv")
