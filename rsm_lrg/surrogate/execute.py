"""Running a design through the surrogate: batches, executors, progress.

:func:`simulate` checks the design, cuts it into batches of rows, evaluates each batch as
NumPy arrays (:func:`rsm_lrg.surrogate.runs.evaluate_rows`; never one Python call per row),
in this process or on any :class:`concurrent.futures.Executor` -- a
``ProcessPoolExecutor`` for local processes, or the executor of a Dask
``distributed.Client`` (``client.get_executor()``) for a cluster -- and joins the batches in
row order. Each row's noise comes from its own stream, keyed by the seed and the row's
index (:mod:`rsm_lrg.surrogate.noise`), so the rows do not depend on the batch size, the
number of workers or the executor.
"""

from __future__ import annotations

import math
from concurrent.futures import Executor, as_completed

import numpy as np

from ..errors import ParameterError
from .design_input import EXTRA_OUTPUT_COLUMNS, OUTPUT_COLUMNS, read_design_arrays
from .noise import resolve_seed
from .progress import progress_bar

__all__ = ["simulate", "simulate_columns", "DEFAULT_NOISE_SD", "DEFAULT_BATCH_ROWS", "MAX_NOISE_SD"]

#: Default reading noise [°C], per thermocouple reading. Table 4's three centre runs
#: (0.034, 0.033, 0.034 °C/min) have a standard deviation of 5.77e-4 °C/min; over 50 min
#: that is 0.029 °C on the end-minus-start rise, which is what independent readings of
#: SD sigma give when two sensors are averaged (SD of the rise = sigma). It is also the
#: SD of rounding to the 0.1 °C display step of the rig's HT9815 (0.1/sqrt(12) = 0.029).
DEFAULT_NOISE_SD = 0.03

#: Largest reading noise [°C] accepted: a thermocouple whose readings scatter by more than
#: 10 °C is broken, and larger values only drown the response (and overflow).
MAX_NOISE_SD = 10.0

#: Rows per batch (a batch is one NumPy evaluation and one task on an executor). Batches are
#: cut at fixed row indices, whatever the executor or the number of workers: the noise of a
#: row never depends on its batch (:mod:`.noise`), and the stick-slip integrator gives each
#: row its own step count (a row run alone equals the row among others; tested), so the
#: rows are the same on one process, N processes or a cluster; fixed cuts keep them
#: bit-identical even where vectorised floating point could differ in the last bit. The
#: compiled stepper integrates each row alone (no time loop shared by a batch), so a batch costs
#: its rows' work plus about 4 % (the thermal network and the per-batch NumPy set-up, measured at
#: 512 rows; 10 % at 256), and 512-row batches let ``--workers N`` keep N workers busy from
#: N × 512 rows on: every worker of 2-4 for designs of a few thousand rows
#: (benchmarks/bench_simulate.py).
DEFAULT_BATCH_ROWS = 512

#: Designs with at least this many rows show a progress bar by default.
PROGRESS_MIN_ROWS = 20000


def _evaluate_batch(arrays, start, seed, noise_sd, duration_min, params, calibration):
    """One batch (module-level so that executors can pickle it)."""
    from .runs import evaluate_rows

    return start, evaluate_rows(arrays, params=params, calibration=calibration, row_start=start,
                                seed=seed, noise_sd=noise_sd, duration_min=duration_min)


def simulate(design, seed=None, noise_sd: float = DEFAULT_NOISE_SD, duration_min: float = 50.0,
             executor: Executor | None = None, *, calibration="default", params=None,
             batch_rows: int | None = None, progress: bool | None = None, row_start: int = 0):
    """Virtual runs of the rig: one row of responses per design row.

    Parameters
    ----------
    design : pandas.DataFrame or rsm_lrg.design.Design
        Columns ``thickness_m`` [m], ``stroke_m`` [m], ``velocity_m_s`` [m/s],
        ``acceleration_m_s2`` [m/s²]; optionally ``stage`` (``rfcms``/``rms``) and any
        parameter of :class:`rsm_lrg.physics.params.LRGParams` as a per-row column. Other
        columns pass through.
    seed : int, numpy.random.Generator or None
        Seed of the reading noise; the same seed gives the same rows. ``None``: fresh
        entropy.
    noise_sd : float
        Standard deviation [°C] of the Gaussian noise on each thermocouple reading (two
        thermocouples, read every minute, averaged; κ by Eq. 18 from the noisy record).
        The SD of κ is then ``noise_sd / duration``. 0 gives the deterministic surrogate;
        at most :data:`MAX_NOISE_SD`.
    duration_min : float
        Test duration [min] for rows without a ``test_duration_min`` column (the paper:
        about 50 min); in [1, 1e5] (:data:`rsm_lrg.surrogate.runs.MAX_DURATION_MIN`).
    executor : concurrent.futures.Executor, optional
        Where batches run: ``None`` in this process; a ``ProcessPoolExecutor``; a Dask
        ``Client.get_executor()``.
    calibration : "default", None, path, mapping or Calibration
        Calibrated parameters: ``"default"`` the shipped ``data/calibration.toml``; ``None``
        the raw physics (paper inputs and the documented assumptions).
    params : LRGParams, optional
        Base physical parameters (default: ``data/lrg_shs15v.toml``). A parameter set away
        from its default here that the calibration also sets raises ``ValueError`` (the
        calibrated value would replace it); a design column of the same name wins over both.
    batch_rows : int, optional
        Rows per batch (default 512; the same for every executor, see
        :data:`DEFAULT_BATCH_ROWS`).
    progress : bool, optional
        Progress bar on stderr (tqdm); default: for designs of 20,000 rows or more.
    row_start : int
        Index of the design's first row in a larger design run piece by piece
        (:mod:`rsm_lrg.surrogate.stream`): each row's noise is keyed by ``row_start`` plus its
        position, so the pieces give the rows of the whole design run at once.

    Returns
    -------
    pandas.DataFrame
        Every input column (a column whose name the surrogate writes is kept as
        ``NAME_input``), then ``tcr_c_per_min`` [°C/min], ``temperature_rise_k`` [K] at the
        end of the test, ``steady_rise_k`` [K], ``wear_volume_m3_per_h`` [m³/h],
        ``sliding_distance_m_per_cycle`` [m], ``heat_w`` [W] into the guide, ``cycle_time_s``.
    """
    import pandas as pd

    if not isinstance(design, pd.DataFrame) and hasattr(design, "to_frame"):
        design = design.to_frame()  # a rsm_lrg.design.Design, or a ColumnTable
    names, result = simulate_columns(design, seed, noise_sd, duration_min, executor, calibration=calibration,
                                     params=params, batch_rows=batch_rows, progress=progress, row_start=row_start)
    out = design.copy()
    out.columns = names[:out.shape[1]]
    for k in names[out.shape[1]:]:
        out[k] = result[k]
    out.attrs.clear()
    return out


def simulate_columns(design, seed=None, noise_sd: float = DEFAULT_NOISE_SD, duration_min: float = 50.0,
                     executor: Executor | None = None, *, calibration="default", params=None,
                     batch_rows: int | None = None, progress: bool | None = None,
                     row_start: int = 0) -> tuple[list[str], dict[str, np.ndarray]]:
    """The work of :func:`simulate` without its table: the names of the output's columns and the
    columns the surrogate computed, for a DataFrame or a :class:`rsm_lrg.table.ColumnTable`
    design (a plain CSV file read without pandas; ``rsm-lrg simulate`` writes it out without
    pandas, :func:`rsm_lrg.readers.write_csv_columns`).

    Parameters
    ----------
    design : pandas.DataFrame or rsm_lrg.table.ColumnTable
        As for :func:`simulate`.
    seed, noise_sd, duration_min, executor, calibration, params, batch_rows, progress, row_start
        As for :func:`simulate`.

    Returns
    -------
    names : list of str
        Every column of the output in order: the design's (a name the surrogate writes renamed
        ``NAME_input``), then the surrogate's.
    columns : dict of str to numpy.ndarray
        The surrogate's columns (``tcr_c_per_min`` [°C/min] ... ``hinge_yields``), one value per
        design row.
    """
    from ..physics.params import LRGParams
    from .calibrate import resolve_calibration
    from .runs import check_duration

    noise_sd = _check_nonneg("noise_sd", noise_sd)
    if noise_sd > MAX_NOISE_SD:
        raise ParameterError("noise_sd", f"noise_sd must be at most {MAX_NOISE_SD:g} degC (the SD of one thermocouple "
                         f"reading), got {noise_sd:g}")
    duration_min = _check_nonneg("duration_min", duration_min)
    duration_min = check_duration(duration_min)
    if params is None:
        params = LRGParams()
    elif not isinstance(params, LRGParams):
        raise TypeError(f"params must be an LRGParams, not {type(params).__name__}")
    cal = resolve_calibration(calibration)
    if cal is not None:
        _check_no_conflict(params, cal.parameter_values())
    seed_int = resolve_seed(seed) if noise_sd > 0 else 0
    arrays = read_design_arrays(design, params)
    n = arrays.n
    names = [str(c) for c in design.columns]
    for c in names:  # an input column the surrogate writes is kept as NAME_input: that name must be free
        if c in OUTPUT_COLUMNS + EXTRA_OUTPUT_COLUMNS and f"{c}_input" in names:
            raise ValueError(f"column {c!r} would be kept as {c + '_input'!r}, which the design already has; "
                             f"rename one of them")

    _executor_workers(executor)
    if isinstance(row_start, (bool, np.bool_)) or not isinstance(row_start, (int, np.integer)) or row_start < 0:
        raise ValueError(f"row_start must be a whole number >= 0, got {row_start!r}")
    row_start = int(row_start)
    if batch_rows is None:
        batch_rows = DEFAULT_BATCH_ROWS
    elif isinstance(batch_rows, (bool, np.bool_)) or not isinstance(batch_rows, (int, np.integer)) or batch_rows < 1:
        raise ValueError(f"batch_rows must be a positive integer, got {batch_rows!r}")
    starts = list(range(0, n, int(batch_rows)))
    show = (n >= PROGRESS_MIN_ROWS) if progress is None else bool(progress)
    bar = progress_bar(n, show)
    pieces = {}
    cal_dict = cal.parameter_values() if cal is not None else {}
    try:
        if executor is None:
            for s in starts:
                e = min(n, s + batch_rows)
                _, out = _evaluate_batch(arrays.take(s, e), row_start + s, seed_int, noise_sd, duration_min, params,
                                         cal_dict)
                pieces[s] = out
                bar.update(e - s)
        else:
            futs = {executor.submit(_evaluate_batch, arrays.take(s, min(n, s + batch_rows)), row_start + s, seed_int,
                                    noise_sd, duration_min, params, cal_dict): s for s in starts}
            for f in as_completed(futs):
                s = futs[f]
                out = f.result()[1]
                pieces[s] = out
                bar.update(min(n, s + batch_rows) - s)
    finally:
        bar.close()

    result = {k: np.concatenate([pieces[s][k] for s in starts]) for k in pieces[starts[0]]}
    inputs = [f"{c}_input" if c in result else c for c in names]
    added = list(OUTPUT_COLUMNS) + [k for k in result if k not in OUTPUT_COLUMNS]
    return inputs + added, {k: result[k] for k in added}


def _check_no_conflict(params, cal_values: dict) -> None:
    """A parameter set away from its default in ``params`` that the calibration also sets
    would be silently replaced by the calibrated value: refuse it, naming both values."""
    from ..physics.params import LRGParams

    default = LRGParams()
    for name, value in cal_values.items():
        mine = getattr(params, name, None)
        if mine is not None and mine != getattr(default, name) and mine != value:
            raise ValueError(f"params sets {name} = {mine!r} but the calibration sets it to {value!r}, which "
                             f"would replace it: drop it from the calibration (calibration={{...}} without "
                             f"{name!r}) or pass calibration=None")


def _check_nonneg(name, x) -> float:
    if isinstance(x, (bool, np.bool_)):
        raise TypeError(f"{name} must be a number, not {x!r}")
    try:
        v = float(x)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a number, not {x!r}") from None
    if not math.isfinite(v) or v < 0:
        raise ParameterError(name, f"{name} must be a finite number >= 0, got {x!r}")
    return v


def _executor_workers(executor) -> int:
    if executor is None:
        return 1
    if not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, not {type(executor).__name__}")
    for attr in ("_max_workers",):
        w = getattr(executor, attr, None)
        if isinstance(w, int) and w > 0:
            return w
    client = getattr(executor, "_client", None)
    if client is not None:
        try:
            return max(1, sum(client.nthreads().values()))
        except Exception:  # noqa: BLE001 - only a sizing hint
            return 2
    return 2
