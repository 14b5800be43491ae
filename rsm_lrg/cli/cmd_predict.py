"""``rsm-lrg predict``: predictions with CI, PI and tolerance intervals, propagation of error
and simulated runs at chosen settings."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    add_block_option,
    add_component_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_json,
    add_model_refinements,
    add_random_effect_options,
    add_where_options,
    check_at_settings,
    probability,
    whole_number,
)

NAME = "predict"
HELP = "predict at settings: CI, PI, tolerance interval, propagation of error, simulated runs"
DESCRIPTION = (
    "Fit the model of each --response (the model options are those of 'fit'; after a --response "
    "they apply to that response only) and predict at the --at setting or at every row of "
    "--points P.csv (actual units): the prediction with its confidence interval for the mean and "
    "prediction interval for one run, and with --tolerance P the tolerance interval that holds a "
    "proportion P of individual runs (two-sided, Wallis' factor as R tolerance::regtol.int; and the "
    "one-sided bounds), all at --confidence C. --factor-sd NAME=SD (actual units) adds the "
    "propagation of error, sqrt(g'Sg + s^2) (Design-Expert's first-order POE). --draws N --seed S "
    "simulates N runs at each setting: factor noise (normal, truncated to the design region), the "
    "model's own uncertainty (multivariate t coefficients; --no-model-uncertainty to leave it out) and "
    "the run-to-run noise; per response mean, SD, quantiles and, with --spec Y=LOW:HIGH, the defect "
    "rate (ppm) and Cpk, and the rate outside any spec."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser, several="a response column (repeatable; model options after it apply to it only)")
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--at", action="extend", nargs="+", metavar="NAME=VALUE",
                       help="the setting in actual units, one NAME=VALUE for every factor (a categoric factor at a "
                            "level)")
    where.add_argument("--points", metavar="P.csv",
                       help="a table of settings, one row each, with a column per factor (actual units)")
    parser.add_argument("--confidence", type=probability, default=0.95, metavar="C",
                        help="confidence level of every interval (default 0.95)")
    parser.add_argument("--tolerance", type=probability, default=None, metavar="P",
                        help="add the tolerance interval for a proportion P of runs (e.g. 0.99)")
    parser.add_argument("--factor-sd", action="append", default=None, metavar="NAME=SD",
                        help="standard deviation of a numeric factor about its setting, in actual units (repeatable): "
                             "the propagation of error, and the simulator's factor noise")
    parser.add_argument("--spec", action="append", default=None, metavar="Y=LOW:HIGH",
                        help="specification limits of a response for the simulator (repeatable; Y=:HIGH or Y=LOW: "
                             "for one limit)")
    parser.add_argument("--draws", type=_draws, default=None, metavar="N",
                        help="simulate N runs at each setting (at most 1e9; above 1e7 the runs are not kept: the "
                             "statistics are streamed, the quantiles still exact)")
    parser.add_argument("--seed", type=whole_number(0), default=None, metavar="S",
                        help="seed of the simulator (default: a fresh one, printed so that the run can be repeated)")
    add_where_options(parser, "draw the simulator's runs")
    bar = parser.add_mutually_exclusive_group()
    bar.add_argument("--progress", dest="progress", action="store_true", default=None,
                     help="always show the simulator's progress bar on stderr")
    bar.add_argument("--no-progress", dest="progress", action="store_false",
                     help="never show it (default: shown above 1e7 draws)")
    parser.add_argument("--no-model-uncertainty", action="store_true",
                        help="the simulator takes the fitted coefficients and residual SD as known")
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser, "prediction for the average block")
    add_random_effect_options(parser)
    add_model_refinements(parser, per_response=True, model=True)
    add_json(parser)
    add_force(parser)


def _draws(text: str) -> int:
    """``--draws``: a whole number from 1 to the simulator's MAX_DRAWS, also written 1e6."""
    import math

    from ..io import quote_user_value
    from ..optimize.simulator import MAX_DRAWS

    q = quote_user_value(text)
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number of runs, got {q}") from None
    if not math.isfinite(v) or v != int(v) or v < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number of runs >= 1, got {q}")
    if v > MAX_DRAWS:
        raise argparse.ArgumentTypeError(f"at most {MAX_DRAWS:.0e} runs, got {q}")
    return int(v)


def _points(args, space, fit):
    """The settings as a frame of the factor columns: from --at (an error names --at) or from
    --points (an error names the file)."""
    import pandas as pd

    from ..io import InputError
    from ..optimize.confirm import parse_settings
    from .paths import read_input

    if args.at:
        try:
            settings = parse_settings(space, args.at)
            frame = pd.DataFrame({k: [v] for k, v in settings.items()})
            fit.predict(frame)  # a blend that misses the total, a setting too far out
        except ValueError as exc:
            raise InputError(f"--at: {exc}") from None
        return frame
    frame = read_input(args, args.points)
    name = str(args.points)
    missing = [n for n in space.names if n not in frame.columns]
    if missing:
        raise InputError(f"--points {name}: no column for factor(s) {', '.join(map(repr, missing))}")
    if len(frame) == 0:
        raise InputError(f"--points {name}: no rows")
    try:
        fit.predict(frame[space.names])
    except ValueError as exc:
        raise InputError(f"--points {name}: {exc}") from None
    return frame[space.names]


def run(args: argparse.Namespace) -> int:
    from ..model import fit
    from ..optimize.prediction import predict_points
    from .errors import about_response
    from .options import check_distinct_responses, response_options
    from .paths import print_notes, print_summary_or_json, read_input
    from .specs import model_spec, random_effect, random_effect_columns

    responses = list(args.response)
    check_distinct_responses(responses)
    specs = [model_spec(response_options(args, i)) for i in range(len(responses))]  # bad options named first
    if args.at:
        check_at_settings(args.at)
    if args.draws is None and (args.seed is not None or args.no_model_uncertainty or args.workers
                               or args.scheduler is not None or args.progress is not None):
        from ..io import InputError

        raise InputError("--seed, --workers, --scheduler, --progress and --no-model-uncertainty belong to the "
                         "simulator: give --draws N too")
    if args.spec and args.draws is None:
        from ..io import InputError

        raise InputError("--spec: the defect rates are counted on simulated runs: give --draws N (and --seed S) too")
    data = read_input(args)
    fits = {}
    notes: list = []
    with about_file(args.data):
        from ..factors import choose_factors

        choice = None if args.component else choose_factors(
            data, args.factor, exclude=responses + ([args.block] if args.block else [])
            + random_effect_columns(args))
        for i, r in enumerate(responses):
            with about_response(r, len(responses) > 1):
                fits[r] = fit(data, r, factors=args.factor if choice is None else choice.space, block=args.block,
                              model=specs[i], components=args.component, **random_effect(args))
            notes += [n for n in fits[r].input_notes if choice is None or n not in choice.notes]
        if choice is not None:
            notes = list(choice.notes) + notes
    first = fits[responses[0]]
    points = _points(args, first.space, first)
    seed = args.seed
    if args.draws is not None and seed is None:
        import secrets

        seed = secrets.randbelow(2**32)  # printed with the result: the run can be repeated
    import contextlib

    from .processes import close_pool, connect_scheduler, process_pool, scheduler_lost, watch_workers

    executor = client = None
    ok = False
    try:
        if args.draws and args.workers and args.workers > 1:
            executor = process_pool(args.workers)
        elif args.draws and args.scheduler is not None:  # an empty address is refused, not run locally
            client = connect_scheduler(args.scheduler, args.scheduler_timeout)
            executor = client.get_executor()
        watch = (watch_workers(client, args.scheduler, args.scheduler_timeout) if client is not None
                 else contextlib.nullcontext())
        with about_file(args.points or args.data), watch:
            try:
                report = predict_points(fits, points, confidence=args.confidence, tolerance=args.tolerance,
                                        factor_sd=args.factor_sd, spec=args.spec, draws=args.draws, seed=seed,
                                        model_uncertainty=not args.no_model_uncertainty, executor=executor,
                                        progress=args.progress)
            except (ValueError, TypeError, KeyboardInterrupt, SystemExit):
                raise
            except Exception as exc:
                if client is None:
                    raise
                raise scheduler_lost(args.scheduler, exc) from None
        ok = True
    finally:
        if executor is not None and client is None:
            close_pool(executor, ok)
        if client is not None:
            with contextlib.suppress(Exception):
                client.close(timeout=5)
    print_notes(dict.fromkeys(str(n) for n in notes))
    print_summary_or_json(args, report, extra={"seed": seed} if args.draws is not None else None)
    return 0


