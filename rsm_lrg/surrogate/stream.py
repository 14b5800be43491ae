"""Virtual runs of a design too large to hold: piece by piece, memory bounded by the piece.

:func:`simulate_chunks` runs each piece of a design (DataFrames, as a CSV or Parquet file is
read a piece at a time, :func:`rsm_lrg.readers.csv_chunks`) through
:func:`rsm_lrg.surrogate.execute.simulate` and yields its rows as they are done, to be written
a piece at a time (:func:`rsm_lrg.readers.write_csv_chunks`). Every row's noise is keyed by
the seed and the row's index in the whole design (``row_start``), so the rows are those of the
design run at once, whatever the piece size; an error names the row in the whole design.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from concurrent.futures import Executor
from dataclasses import dataclass, field
from typing import Any

__all__ = ["simulate_chunks", "StreamTally"]

_ROW = re.compile(r"\brow (\d+)")


@dataclass
class StreamTally:
    """What the pieces held, for the closing messages: rows run, the rows (1-based, the first
    ten) whose hinge would yield and their count, and the output columns."""

    rows: int = 0
    yielding: int = 0
    first_yielding: list[int] = field(default_factory=list)
    columns: list[str] = field(default_factory=list)


def _renumber(message: str, offset: int) -> str:
    """``row N`` of a piece as ``row N + offset`` of the whole design (the first mention)."""
    return _ROW.sub(lambda m: f"row {int(m.group(1)) + offset}", message, count=1)


def simulate_chunks(chunks: Iterable[Any], *, seed: int, noise_sd: float, duration_min: float = 50.0,
                    executor: Executor | None = None, calibration: Any = "default", params: Any = None,
                    batch_rows: int | None = None, tally: StreamTally | None = None) -> Iterator[Any]:
    """Run the pieces of a design through the surrogate, yielding each piece's runs.

    Parameters
    ----------
    chunks : iterable of pandas.DataFrame
        The design's rows, in order, a piece at a time (the same columns in every piece).
    seed : int
        Seed of the reading noise (one seed for the whole design; ``0`` when ``noise_sd`` is 0).
    noise_sd, duration_min, executor, calibration, params, batch_rows
        As for :func:`rsm_lrg.surrogate.execute.simulate` (the calibration is resolved once).
    tally : StreamTally, optional
        Filled in as the pieces are run.

    Yields
    ------
    pandas.DataFrame
        The runs of each piece (the columns of :func:`~rsm_lrg.surrogate.execute.simulate`).

    Raises
    ------
    ValueError
        A bad value in a piece, naming the column and the row of the whole design; a design
        with no rows.
    """
    import numpy as np

    from .calibrate import resolve_calibration
    from .execute import simulate

    cal = resolve_calibration(calibration)
    tally = tally if tally is not None else StreamTally()
    offset = 0
    for piece in chunks:
        if len(piece) == 0:
            continue
        piece = piece.reset_index(drop=True)
        try:
            out = simulate(piece, seed=seed, noise_sd=noise_sd, duration_min=duration_min, executor=executor,
                           calibration=cal, params=params, batch_rows=batch_rows, progress=False, row_start=offset)
        except ValueError as exc:
            raise ValueError(_renumber(str(exc), offset)) from None
        if "hinge_yields" in out.columns:
            y = np.flatnonzero(out["hinge_yields"].to_numpy(dtype=bool))
            tally.yielding += int(y.size)
            tally.first_yielding += [int(i) + offset + 1 for i in y[: max(0, 10 - len(tally.first_yielding))]]
        offset += len(piece)
        tally.rows = offset
        tally.columns = [str(c) for c in out.columns]
        yield out
    if offset == 0:
        raise ValueError("the design has no rows")
