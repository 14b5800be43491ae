"""The paper's published data (and a published mixture example), shipped inside the package.

The files live in ``rsm_lrg/data/`` (package data) and, for people reading the repository,
in ``data/`` at the top level; ``tests/test_datasets.py`` keeps the two identical.
Sources are listed in ``data/README.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

__all__ = ["DATASETS", "Dataset", "data_path", "dataset", "load_table4", "load_table3", "load_table5",
           "load_equation19", "load_mixture_etch", "load_cake_split_plot"]


@dataclass(frozen=True)
class Dataset:
    """One shipped table, as ``rsm-lrg datasets`` lists and writes it.

    Parameters
    ----------
    name : str
        The name given on the command line (``rsm-lrg datasets table4``).
    file : str
        The file name inside ``rsm_lrg/data/`` (and ``data/`` of the repository).
    title : str
        One line saying what the table holds and where it comes from.
    """

    name: str
    file: str
    title: str


#: The shipped tables, in the order ``rsm-lrg datasets`` lists them.
DATASETS: tuple[Dataset, ...] = (
    Dataset("table4", "table4.csv", "the paper's 27 Box-Behnken runs with the measured TCR kappa "
            "[degC/min] (Su, Zhang & Yang 2023, Table 4)"),
    Dataset("table3", "table3_levels.csv", "factor letters, names, units and low/centre/high levels "
            "(Table 3)"),
    Dataset("table5", "table5_anova.csv", "the ANOVA of kappa as printed in the paper (Table 5)"),
    Dataset("equation19", "equation19_coded.csv", "the 15 coded coefficients of the fitted quadratic (Eq. 19)"),
    Dataset("mixture-etch", "mixture_etch.csv", "a mixture experiment: plasma etch rate of 14 blends of "
            "x1, x2, x3 (Myers & Montgomery 2002, Table 12.4)"),
    Dataset("cake-split-plot", "cake_split_plot.csv", "a split-plot study: 11 cakes in 4 oven runs, whole "
            "plot Ovenrun (Lawson 2015, daewr cakeb)"),
)


def dataset(name: str) -> Dataset:
    """The shipped table called ``name`` (its :data:`DATASETS` name or its file name).

    Parameters
    ----------
    name : str
        ``"table4"``, ``"mixture-etch"``, ... or the file name (``"table4.csv"``).

    Returns
    -------
    Dataset

    Raises
    ------
    ValueError
        When no shipped table has that name; the message lists the names.

    >>> dataset("table4.csv").name
    'table4'
    """
    for d in DATASETS:
        if name in (d.name, d.file, d.name.replace("-", "_")):
            return d
    raise ValueError(f"no shipped data set {name!r}; choose from {', '.join(d.name for d in DATASETS)}")


def data_path(name: str) -> Path:
    """Filesystem path of a shipped data file.

    Parameters
    ----------
    name : str
        The file name inside ``rsm_lrg/data/`` (``"table4.csv"``, ``"lrg_shs15v.toml"``, ...).

    Returns
    -------
    pathlib.Path
    """
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

    Returns
    -------
    pandas.DataFrame
        Table 4: the 27 runs (factor columns in SI units, response ``tcr_c_per_min`` [°C/min]).
    """
    return _csv("table4.csv")


def load_table3():
    """Table 3: factor letters, names, units and the low/centre/high levels.

    Returns
    -------
    pandas.DataFrame
        Table 3: the factors' levels (one row per factor).
    """
    return _csv("table3_levels.csv")


def load_table5():
    """Table 5: the paper's ANOVA as printed (p values kept as text, e.g. ``<0.0001``).

    Returns
    -------
    pandas.DataFrame
        Table 5: the paper's ANOVA, p values as printed (text).
    """
    import pandas as pd

    return pd.read_csv(data_path("table5_anova.csv"), dtype={"p_value": str})


def load_equation19():
    """Eq. 19: the coded quadratic coefficients of κ, as a Series indexed by term.

    Returns
    -------
    pandas.DataFrame
        Eq. 19's coded coefficients, one row per term.
    """
    return _csv("equation19_coded.csv").set_index("term")["coefficient"]


def load_mixture_etch():
    """A published mixture experiment: the plasma etch rate (``erate``) of 14 blends of three
    components ``x1``, ``x2``, ``x3`` (a simplex-centroid design with the three axial check
    blends, vertices and centroid replicated). Myers & Montgomery, *Response Surface
    Methodology*, 2nd ed. (2002), Table 12.4, as shipped in R mixexp's ``etch`` data set.

    >>> load_mixture_etch().shape
    (14, 4)

    Returns
    -------
    pandas.DataFrame
        The 14 blends (``x1``, ``x2``, ``x3``, proportions) and ``erate`` [Å/min].
    """
    return _csv("mixture_etch.csv")


def load_cake_split_plot():
    """A split-plot response surface: 11 cakes baked in 4 oven runs (``Ovenrun``, the whole
    plot); ``x1`` (coded, hard to change) is constant within an oven run, ``x2`` (coded)
    varies within it; response ``y``. Lawson, *Design and Analysis of Experiments with R*
    (2015), ch. 10, R package daewr's ``cakeb``.

    >>> load_cake_split_plot().shape[0]
    11

    Returns
    -------
    pandas.DataFrame
        The 11 cakes: ``Ovenrun``, ``x1``, ``x2`` (coded) and ``y``.
    """
    return _csv("cake_split_plot.csv")
