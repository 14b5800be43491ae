"""``rsm-lrg loop``: the closed loop of a computer experiment: an initial space-filling design,
then evaluate -> fit a Gaussian process -> choose the next runs by expected improvement ->
evaluate ... until the budget is spent; every round is kept in a study directory that the
same command resumes (:mod:`rsm_lrg.cli.loop_study`)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from .gp_fit import KERNEL_CHOICES, TREND_CHOICES, length_scale_bounds
from .options import add_json, number, whole_number

if TYPE_CHECKING:
    from .loop_study import LoopOptions

NAME = "loop"
HELP = "closed loop: space-filling design, then GP + expected improvement rounds, resumable (study directory)"
DESCRIPTION = (
    "Run a computer experiment in a closed loop: a Latin hypercube of --initial runs over the "
    "--factor box, then rounds of: fit a Gaussian process to every run (as 'fit --model gp', its length-scales at most 2 "
    "times each factor's range: R DiceKriging km's default, as 'suggest'), choose "
    "--batch new settings by expected improvement (Kriging Believer, as 'suggest'), evaluate them; "
    "until --budget evaluations are spent or the largest expected improvement is below --ei-tol times "
    "the range of the responses. --surrogate evaluates with this project's calibrated surrogate "
    "(deterministic, noise 0; its design columns not given as factors are held at the parameter "
    "file's values); --evaluate \"COMMAND {in} {out}\" runs any command (split as a shell would, run "
    "without one) that reads the design CSV {in} and writes a CSV {out} with the response column, one "
    "row per design row. Every round is written to STUDY_DIR (study.json, round_NNN/design.csv, "
    "responses.csv, model.json, suggestions.json; at the end final_model.json and report.html); the "
    "same command on an existing STUDY_DIR resumes it without repeating a finished evaluation."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--factor", action="append", required=True, metavar="NAME=LOW:HIGH",
                        help="a numeric factor and its range in actual units (repeatable; at least one)")
    parser.add_argument("--response", required=True, metavar="Y", help="the response column to optimise")
    parser.add_argument("--goal", default="minimize", metavar="minimize|maximize|target=V",
                        help="what the loop improves (default minimize)")
    parser.add_argument("--budget", type=whole_number(2, 10000), required=True, metavar="N",
                        help="evaluations in all, the initial design included")
    parser.add_argument("--initial", type=whole_number(2, 10000), default=None, metavar="M",
                        help="runs of the initial Latin hypercube (default max(5, 4 x factors), at most the budget)")
    parser.add_argument("--batch", type=whole_number(1, 1000), default=1, metavar="Q",
                        help="new settings per round (default 1)")
    parser.add_argument("--seed", type=whole_number(0), default=0, metavar="S",
                        help="seed of the initial design, the likelihood's starts and the searches (default 0)")
    how = parser.add_mutually_exclusive_group(required=True)
    how.add_argument("--surrogate", action="store_true",
                     help="evaluate with the calibrated physics surrogate (rsm_lrg.simulate, noise 0)")
    how.add_argument("--evaluate", default=None, metavar='"COMMAND {in} {out}"',
                     help="a command that reads the design CSV {in} and writes the responses CSV {out}")
    parser.add_argument("--workers", type=whole_number(1, 256), default=1, metavar="K",
                        help="--evaluate: run the command on up to K pieces of a round at once (default 1)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="--surrogate: run each round's rows on a Dask distributed scheduler (e.g. "
                             "tcp://10.0.0.5:8786; the same numbers as in this process)")
    parser.add_argument("--scheduler-timeout", type=number(0, 3600, above=True), default=60.0, metavar="S",
                        help="seconds the --scheduler has to answer before the run is refused (default 60)")
    parser.add_argument("--evaluate-timeout", type=number(0, 1e7, above=True), default=600.0, metavar="SECONDS",
                        help="--evaluate: seconds one call may run before it is stopped (default 600)")
    parser.add_argument("--ei-tol", type=number(0, 1), default=1e-6, metavar="R",
                        help="stop when the largest expected improvement is at most R times the range of the "
                             "responses (default 1e-6; 0: spend the whole budget)")
    parser.add_argument("--kernel", default="matern52", choices=list(KERNEL_CHOICES),
                        help="the GP's correlation kernel (default matern52)")
    parser.add_argument("--trend", default="constant", choices=list(TREND_CHOICES),
                        help="the GP's trend (default constant)")
    parser.add_argument("--length-scale-bounds", default=None, type=length_scale_bounds, metavar="LOW:HIGH",
                        help="bounds of the GP's estimated length-scales, as multiples of each factor's coded range "
                             "in the runs (default 0.001:2, R DiceKriging km's upper bound, as 'suggest'; a resumed "
                             "study keeps its own: 0.001:10 for a study begun before this option)")
    parser.add_argument("--no-progress", action="store_true", help="no progress line per round on stderr")
    parser.add_argument("-o", "--output", required=True, metavar="STUDY_DIR",
                        help="the study directory (made when missing; an existing study is resumed)")
    add_json(parser)


def outputs(args: argparse.Namespace) -> list[tuple[str, str]]:
    """Checked before the run: the --json file. STUDY_DIR is a directory the loop writes
    round by round (each file atomically), so it is checked by the run itself."""
    import os

    from ..io import InputError

    out = str(args.output)
    if not out.strip():
        raise InputError("-o/--output: an empty path was given")
    if os.path.lexists(out) and not os.path.isdir(out):
        raise InputError(f"-o/--output {out}: exists and is not a directory (give a study directory)")
    return [("--json", args.json)] if args.json is not None else []


def _options(args: argparse.Namespace) -> LoopOptions:
    from ..design.core import as_factor_space
    from ..io import InputError, quote_user_value
    from ..model.build.goals import parse_goal
    from .loop_study import LoopOptions, surrogate_factor_names

    try:
        space = as_factor_space(args.factor)
    except ValueError as exc:
        raise InputError(f"--factor: {exc}") from None
    for f in space.factors:
        if f.kind != "numeric":
            raise InputError(f"--factor {f.name}: the loop takes numeric factors NAME=LOW:HIGH only")
    for spec in args.factor:
        if ":" not in spec.split("=", 1)[-1] or "=" not in spec:
            raise InputError(f"--factor {quote_user_value(spec)}: give the range, NAME=LOW:HIGH")
    try:
        kind, target = parse_goal(args.goal)
    except ValueError as exc:
        raise InputError(f"--goal: {exc}") from None
    if args.response in space.names:
        raise InputError(f"--response {quote_user_value(args.response)}: is also a --factor")
    d = len(space.factors)
    initial = args.initial if args.initial is not None else min(args.budget, max(5, 4 * d))
    if initial > args.budget:
        raise InputError(f"--initial {initial}: more than the --budget {args.budget}")
    if args.surrogate:
        from ..surrogate.design_input import OUTPUT_COLUMNS

        known, _ = surrogate_factor_names()
        for name in space.names:
            if name not in known:
                raise InputError(f"--factor {quote_user_value(name)}: not an input of the surrogate (its design "
                                 f"columns: thickness_m, stroke_m, velocity_m_s, acceleration_m_s2, or a parameter)")
        if args.response not in OUTPUT_COLUMNS:
            raise InputError(f"--response {quote_user_value(args.response)}: not a response of the surrogate "
                             f"({', '.join(OUTPUT_COLUMNS)})")
        if args.workers != 1:
            raise InputError("--workers: only with --evaluate (the surrogate runs in this process)")
        evaluator = {"kind": "surrogate", "noise_sd": 0.0, "calibration": "default"}
    else:
        import shlex

        try:
            argv = shlex.split(args.evaluate)
        except ValueError as exc:
            raise InputError(f"--evaluate: cannot split the command ({exc})") from None
        if not argv:
            raise InputError("--evaluate: an empty command was given")
        joined = " ".join(argv)
        for token in ("{in}", "{out}"):
            if token not in joined:
                raise InputError(f"--evaluate: the command has no {token} (it reads the design CSV {{in}} and "
                                 f"writes the responses CSV {{out}})")
        if args.scheduler is not None:
            raise InputError("--scheduler: only with --surrogate (an --evaluate command runs here, on up to "
                             "--workers pieces at once)")
        evaluator = {"kind": "command", "command": args.evaluate}
    del kind, target
    return LoopOptions(factors=list(args.factor), response=args.response, goal=args.goal.strip().lower(),
                       budget=args.budget, initial=initial, batch=args.batch, seed=args.seed, evaluator=evaluator,
                       ei_tol=args.ei_tol, kernel=args.kernel, trend=args.trend,
                       length_scale_bounds=None if args.length_scale_bounds is None else list(args.length_scale_bounds),
                       workers=args.workers,
                       timeout=args.evaluate_timeout, progress=not args.no_progress)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..io import dump_json
    from .loop_study import run_study
    from .processes import cluster_failures, connect_scheduler

    opts = _options(args)
    client = None
    if args.scheduler is not None:  # an empty address is refused, not run locally
        client = connect_scheduler(args.scheduler, args.scheduler_timeout)
        opts.executor = client.get_executor()
    try:
        with cluster_failures(args.scheduler):
            summary = run_study(Path(args.output), opts)
    finally:
        if client is not None:
            client.close()
    if args.json and args.json != "-":
        dump_json(summary, args.json)
    if args.json == "-":
        dump_json(summary, "-")
        return 0
    best = summary["best"]
    at = ", ".join(f"{k} = {v:.6g}" for k, v in best["setting"].items())
    print(f"Study: {args.output} ({summary['evaluations']} evaluations, {summary['rounds']} rounds; stopped: "
          f"{summary['stopped_because']})")
    print(f"Best {summary['response']} = {best['observed']:.6g} at {at} (evaluation {best['evaluation']})")
    print(f"GP prediction there: {best['predicted']:.6g}, 95% prediction interval "
          f"[{best['pi_low']:.6g}, {best['pi_high']:.6g}]; LOO Q2 {summary['loo']['q2']:.4f}")
    print(f"Report: {Path(args.output) / 'report.html'}")
    return 0
