"""The paper layer: the reproduction of Su, Zhang & Yang (2023), *Machines* 11(3), 358.

It sits above the report and below the command line: :func:`reproduce` coordinates the
physics, the surrogate, the model and the optimiser and compares every number the paper
prints with the toolkit's (:mod:`rsm_lrg.paper.reproduction`); the report layer only presents
the result (:mod:`rsm_lrg.report.reproduction_page`).
"""

from .reproduction import (
    VERDICTS,
    Reproduction,
    Row,
    last_digit_unit,
    reproduce,
    reproduction_html,
    write_reproduction,
)

__all__ = ["reproduce", "Reproduction", "Row", "VERDICTS", "last_digit_unit", "reproduction_html",
           "write_reproduction"]
