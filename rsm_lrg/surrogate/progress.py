"""A progress bar on stderr for long surrogate work (virtual runs, calibration fits).

Shared by :mod:`rsm_lrg.surrogate.execute` and :mod:`rsm_lrg.surrogate.calibrate`; the bar
is tqdm's (the ``parallel`` extra) and nothing is shown without it or when not asked for.
"""

from __future__ import annotations

import sys
from typing import Any

__all__ = ["NoBar", "progress_bar"]


class NoBar:
    """A progress bar that shows nothing (``update`` and ``close`` do nothing)."""

    def update(self, n: int) -> None:
        pass

    def close(self) -> None:
        pass


def progress_bar(total: int, show: bool, desc: str = "virtual runs", unit: str = "run") -> Any:
    """A tqdm bar on stderr counting ``total`` ``unit`` s, or a :class:`NoBar` when ``show`` is
    false or tqdm is not installed."""
    if not show:
        return NoBar()
    try:
        from tqdm import tqdm
    except ImportError:  # tqdm is in the 'parallel' extra
        return NoBar()
    return tqdm(total=total, unit=unit, desc=desc, file=sys.stderr, dynamic_ncols=True)
