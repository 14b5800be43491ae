"""``rsm-lrg simulate``: virtual runs of the physics surrogate, one row per design row."""

from __future__ import annotations

import argparse
from collections.abc import Iterable
from typing import Any, BinaryIO

from .errors import about_file
from .options import add_force, add_reader_options, add_where_options, whole_number

NAME = "simulate"
HELP = "virtual runs of the physics surrogate, one row per design row"
DESCRIPTION = (
    "Run a design through the physics surrogate as if the rig of Su, Zhang & Yang (2023, "
    "Section 4) had run it: motion profile, stage dynamics with the hinge thickness (column "
    "stage = rfcms, the default, or rms), cycle-averaged friction heat, the thermal model over "
    "the test, thermocouple readings every minute (two sensors, averaged) and the temperature "
    "change rate by Eq. 18, plus temperature rise, steady rise, Archard wear per hour and "
    "sliding distance per cycle. Every input column is kept. Uses the calibration in "
    "data/calibration.toml unless --calibration PATH or --uncalibrated. Rows where a hinge leaf "
    "would yield (peak stress above hinge_yield_pa; in Table 3's box the 0.1 mm leaf at hard "
    "accelerations and high speeds) are kept, flagged in hinge_yields and named in one warning: the "
    "model keeps the elastic law there, so those rows are outside its validity."
)


def _nonneg_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not v >= 0 or v == float("inf"):
        raise argparse.ArgumentTypeError(f"expected a finite number >= 0, got {text!r}")
    return v


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("design", metavar="DESIGN.csv",
                   help="design: thickness_m, stroke_m, velocity_m_s, acceleration_m_s2 [, stage, parameter columns]")
    add_reader_options(p)
    p.add_argument("--seed", type=whole_number(0), default=None, metavar="N",
                   help="seed of the reading noise (default: drawn and printed on stderr)")
    p.add_argument("--noise-sd", type=_nonneg_float, default=None, metavar="X",
                   help="SD [degC] of the Gaussian noise on each thermocouple reading (two sensors, read "
                        "every minute, averaged); kappa's SD is X / duration. 0 = deterministic (default 0.03)")
    p.add_argument("--duration-min", type=_nonneg_float, default=50.0, metavar="M",
                   help="test duration [min] for rows without a test_duration_min column (default 50)")
    add_where_options(p, "run batches")
    cal = p.add_mutually_exclusive_group()
    cal.add_argument("--calibration", default=None, metavar="PATH",
                     help="calibration TOML (default: the shipped data/calibration.toml)")
    cal.add_argument("--uncalibrated", action="store_true",
                     help="the raw physics: the paper's inputs and the documented assumptions")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="override a physical parameter for every row (repeatable): a name of "
                        "`rsm-lrg physics --list-params` or heat_partition, drive_friction_n, drive_viscous_n_s_m; "
                        "it replaces a calibrated value of the same name; not a design factor or a design column")
    prog = p.add_mutually_exclusive_group()
    prog.add_argument("--progress", dest="progress", action="store_true", default=None,
                      help="always show a progress bar on stderr")
    prog.add_argument("--no-progress", dest="progress", action="store_false",
                      help="never show a progress bar (default: for 20,000 rows or more)")
    p.add_argument("--chunk-rows", type=whole_number(1000, 10_000_000), default=STREAM_CHUNK_ROWS, metavar="N",
                   help="a CSV or Parquet design of more rows is run N rows at a time, read and written piece by "
                        f"piece, memory bounded by N (default {STREAM_CHUNK_ROWS:,})")
    p.add_argument("-o", "--output", required=True, metavar="PATH",
                   help="the runs to write: CSV, or Parquet when PATH ends in .parquet")
    add_force(p)


#: Rows of a piece when a large design is run piece by piece (``--chunk-rows``).
STREAM_CHUNK_ROWS = 100_000


def _open_stream(args):
    """``(ReadAs, first piece, the other pieces)`` when the design is a CSV or Parquet file of
    more than ``--chunk-rows`` rows (read piece by piece), else None (read whole)."""
    from itertools import chain

    from .. import readers
    from ..io import InputError, open_input, show_path

    if str(args.design) == "-" or getattr(args, "sheet", None) is not None:
        return None
    fh = open_input(args.design, "design")
    try:
        head = fh.read(16)
        fmt = readers.detect_format(head, "." + str(args.design).rsplit(".", 1)[-1] if "." in str(args.design) else "")
        if fmt not in ("csv", "parquet") or head.startswith((b"\xff\xfe", b"\xfe\xff")):
            fh.close()
            return None
        if readers.count_rows(fh, fmt) <= args.chunk_rows:
            fh.close()
            return None
        if fmt == "parquet":
            if args.sep is not None or args.decimal != ".":
                raise readers.TableError("--sep and --decimal are for CSV text; this is PARQUET")
            how, pieces = readers.parquet_chunks(fh, chunk_rows=args.chunk_rows)
        else:
            how, pieces = readers.csv_chunks(fh, sep=args.sep, decimal=args.decimal, chunk_rows=args.chunk_rows)
        first = next(pieces)
    except readers.TableError as exc:
        fh.close()
        raise InputError(f"{show_path(args.design)}: {exc}") from None
    except BaseException:
        fh.close()
        raise
    return how, first, chain([first], pieces), fh


def _calibration(args):
    """The calibration the options ask for (read and checked before the design)."""
    if args.uncalibrated:
        return None
    if args.calibration:
        from ..surrogate.calibrate import load_calibration

        return load_calibration(args.calibration)
    return "default"


#: ``--param`` names that are factors of the design (the design's column wins on every row).
DESIGN_FACTOR_PARAMS = {"hinge_thickness_m": "thickness_m", "stroke_m": "stroke_m",
                        "velocity_m_s": "velocity_m_s", "acceleration_m_s2": "acceleration_m_s2"}


def _surrogate_assignments(items):
    """Split ``--param`` items into those of LRGParams (returned as they are) and the
    surrogate's own parameters (``heat_partition``, ``drive_friction_n``,
    ``drive_viscous_n_s_m``: ``{name: float}``, checked against their documented bounds)."""
    from ..io import InputError, quote_user_value
    from ..surrogate.calibrate import documented_bounds
    from ..surrogate.runs import SURROGATE_PARAMETERS

    rest, own = [], {}
    for item in items:
        name, eq, text = item.partition("=")
        name = name.strip()
        if not eq or name not in SURROGATE_PARAMETERS:
            rest.append(item)
            continue
        if name in own:
            raise InputError(f"--param {quote_user_value(item, 60)}: {name} is given more than once")
        try:
            v = float(text)
        except ValueError:
            v = None
        lo, hi, _ = documented_bounds(name)
        if v is None or not lo <= v <= hi:
            unit = SURROGATE_PARAMETERS[name][1]
            raise InputError(f"--param {quote_user_value(item, 60)}: {name} must be a number in "
                             f"[{lo:g}, {hi:g}]" + ("" if unit == "1" else f" {unit}"))
        own[name] = v
    return rest, own


def _calibration_with_overrides(calibration, overrides, surrogate):
    """The calibration to run with: ``--param`` wins over a calibrated value of the same name
    (said on stderr); the surrogate's own ``--param`` values join it."""
    import sys

    if not overrides and not surrogate:
        return calibration
    from ..surrogate.calibrate import resolve_calibration

    cal = resolve_calibration(calibration)
    values = cal.parameter_values() if cal is not None else {}
    given = {**overrides, **surrogate}
    for name in sorted(set(values) & set(given)):
        print(f"simulate: --param {name}={given[name]!r} replaces the calibrated {values[name]!r}", file=sys.stderr)
    values = {k: v for k, v in values.items() if k not in given}
    values.update(surrogate)
    return values if values else None


def run(args) -> int:
    import sys
    from pathlib import Path

    import numpy as np

    from ..io import InputError, check_output, write_output
    from ..physics.params import LRGParams, parse_assignments
    from ..surrogate.execute import DEFAULT_NOISE_SD, MAX_NOISE_SD, simulate, simulate_columns
    from ..surrogate.noise import resolve_seed
    from ..surrogate.runs import check_duration
    from ..table import is_column_table
    from .paths import read_input

    out_path = Path(args.output)
    check_output(out_path, force=args.force, option="-o/--output")
    try:
        check_duration(args.duration_min, "--duration-min")
    except ValueError as exc:
        raise InputError(str(exc)) from None
    if args.noise_sd is not None and args.noise_sd > MAX_NOISE_SD:
        raise InputError(f"--noise-sd must be at most {MAX_NOISE_SD:g} degC (the SD of one thermocouple "
                         f"reading), got {args.noise_sd:g}")
    lrg_items, surrogate = _surrogate_assignments(args.param)
    overrides = parse_assignments(lrg_items)
    for name, option in (("test_duration_min", "--duration-min"),):
        if name in overrides:
            raise InputError(f"--param {name}: give the test duration with {option} (or a {name} column)")
    for name in overrides:
        if name in DESIGN_FACTOR_PARAMS:
            raise InputError(f"--param {name}: a factor of the design; give it in the design's column "
                             f"{DESIGN_FACTOR_PARAMS[name]!r}, row by row")
    params = LRGParams().with_overrides(**overrides) if overrides else LRGParams()
    if overrides:  # parameters that no design can rescue are the option's fault, not the file's
        from ..surrogate.runs import thermal_unit_response

        try:
            thermal_unit_response(params.to_dict(), 1.0)
        except ValueError as exc:
            raise InputError(f"--param: {exc}") from None
    calibration = _calibration(args)
    streamed = _open_stream(args)
    parquet = out_path.suffix.lower() in (".parquet", ".pq")
    if streamed is None:  # a plain CSV design is read (and its runs written as CSV) without pandas
        design = read_input(args, args.design, column_table=not parquet)
    else:  # read, run and written piece by piece
        how, design, pieces, source = streamed
        args.notes_at_end = [f"read {args.design}: {how.describe()}, {args.chunk_rows:,} rows at a time"]
    for name in (*overrides, *surrogate):  # the design's column would silently win
        if name in design.columns:
            raise InputError(f"--param {name}: {args.design}: the design's column {name!r} sets it row by row; "
                             f"drop the option or the column")
    calibration = _calibration_with_overrides(calibration, overrides, surrogate)
    noise = DEFAULT_NOISE_SD if args.noise_sd is None else args.noise_sd
    seed = args.seed
    if seed is None and noise > 0:
        seed = resolve_seed(None)
        drawn = True
    else:
        drawn = False

    # a local pool whose workers die with this process and are killed at once on an error or a
    # signal, or a scheduler that must answer within --scheduler-timeout (rsm_lrg.cli.processes)
    from .processes import close_pool, cluster_failures, connect_scheduler, process_pool, watch_workers

    executor = client = None
    ok = False
    try:
        if args.workers and args.workers > 1:
            executor = process_pool(args.workers)
        elif args.scheduler is not None:  # an empty address is refused, not run locally
            client = connect_scheduler(args.scheduler, args.scheduler_timeout)
            executor = client.get_executor()
        from .. import readers
        from ..surrogate.stream import StreamTally, simulate_chunks

        tally = StreamTally()
        import contextlib

        watch = (watch_workers(client, args.scheduler, args.scheduler_timeout) if client is not None
                 else contextlib.nullcontext())
        with about_file(args.design), cluster_failures(args.scheduler if client is not None else None,
                                                      args.workers if executor is not None and client is None
                                                      else None), watch:
            plain: tuple[list[str], dict] | None = None
            if streamed is None and is_column_table(design):  # the columns, no DataFrame
                names, added = simulate_columns(design, seed=seed, noise_sd=noise, duration_min=args.duration_min,
                                                executor=executor, calibration=calibration, params=params,
                                                progress=args.progress)
                plain = (names, {**dict(zip(names, (design[c] for c in design.columns))), **added})
                frames: Iterable[Any] = []
            elif streamed is None:
                runs = simulate(design, seed=seed, noise_sd=noise, duration_min=args.duration_min,
                                executor=executor, calibration=calibration, params=params,
                                progress=args.progress)
                frames = [runs]
            else:
                frames = simulate_chunks(pieces, seed=seed, noise_sd=noise, duration_min=args.duration_min,
                                         executor=executor, calibration=calibration, params=params, tally=tally)
            writer = readers.write_parquet_chunks if parquet else readers.write_csv_chunks
            try:
                def fill(fh: BinaryIO) -> None:
                    if plain is not None:
                        readers.write_csv_columns(fh, *plain)
                    else:
                        writer(fh, frames)

                write_output(out_path, fill, force=args.force)
            except readers.TableError as exc:
                raise ValueError(str(exc)) from None
        ok = True
    finally:
        if streamed is not None:
            source.close()
        if executor is not None and client is None:
            close_pool(executor, ok)
        if client is not None:
            import contextlib

            with contextlib.suppress(Exception):
                client.close(timeout=5)
    if streamed is None:
        if plain is not None:
            out_names, out_columns = plain
            n_runs = len(design)
        else:
            out_names, out_columns, n_runs = [str(c) for c in runs.columns], runs, len(runs)
        yields = (np.asarray(out_columns["hinge_yields"], dtype=bool) if "hinge_yields" in out_names
                  else np.zeros(0, dtype=bool))
        tally = StreamTally(n_runs, int(yields.sum()), [int(i) + 1 for i in np.flatnonzero(yields)[:10]],
                            out_names)
    note = f" (noise seed drawn: rerun with --seed {seed} to repeat)" if drawn else ""
    print(f"simulate: {tally.rows} runs -> {out_path}{note}", file=sys.stderr)
    names = [str(c) for c in design.columns]
    kept = [c for c in names if f"{c}_input" in tally.columns and f"{c}_input" not in names]
    if kept:
        print(f"simulate: the design's column(s) {', '.join(kept)} are kept as "
              f"{', '.join(c + '_input' for c in kept)} (the surrogate writes those names)", file=sys.stderr)
    if tally.yielding:
        rows = [str(i) for i in tally.first_yielding]
        print(f"simulate: WARNING: the hinge leaves would yield in {tally.yielding} row(s) "
              f"(data rows {', '.join(rows)}{' ...' if tally.yielding > 10 else ''}): peak stress "
              f"above hinge_yield_pa (columns hinge_peak_stress_pa, hinge_yields). The model keeps the elastic "
              f"law there, so those rows are outside its validity (a real leaf would take a permanent set); in "
              f"Table 3's box only the 0.1 mm leaf yields, at hard accelerations and high speeds",
              file=sys.stderr)
    return 0
