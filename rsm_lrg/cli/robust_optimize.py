"""``rsm-lrg optimize`` on interval ends and the propagation of error: the options
``--interval ci|pi|ti`` (per response, like ``--goal``), ``--factor-sd NAME=SD``,
``--confidence C``, ``--tolerance P`` and the goal ``poe``, and the run that uses them
(:func:`rsm_lrg.optimize.robust.optimize_robust`). ``cmd_optimize`` adds the options and hands
over when one of them is given."""

from __future__ import annotations

import argparse

from .options import ResponseValue, probability

__all__ = ["add_robust_options", "robust_requested", "run_robust"]


def add_robust_options(parser: argparse.ArgumentParser) -> None:
    """The options of an optimum on interval ends or on the POE."""
    g = parser.add_argument_group("optimising on intervals and on the propagation of error")
    g.add_argument("--interval", action=ResponseValue, default=None, metavar="ci|pi|ti",
                   help="judge the response before it on an interval end, not the mean: maximize raises the lower "
                        "end, minimize lowers the upper end, a target or range keeps both ends in (per response)")
    g.add_argument("--factor-sd", action="append", default=None, metavar="NAME=SD",
                   help="SD of a numeric factor in actual units (repeatable): the POE at the optimum, and what "
                        "--goal poe minimises")
    g.add_argument("--confidence", type=probability, default=0.95, metavar="C",
                   help="confidence of the intervals of --interval (default 0.95)")
    g.add_argument("--tolerance", type=probability, default=0.99, metavar="P",
                   help="proportion of runs of the tolerance interval of --interval ti (default 0.99)")


def robust_requested(args: argparse.Namespace) -> bool:
    """Whether the run needs the interval/POE optimiser: ``--interval``, ``--factor-sd`` or a
    ``poe`` goal."""
    goals = [v[1] if isinstance(v, tuple) else v for v in (getattr(args, "goal", None) or [])]
    return bool(getattr(args, "interval", None) or getattr(args, "factor_sd", None)
                or any(str(g).strip().lower() == "poe" for g in goals if g is not None))


def run_robust(args: argparse.Namespace) -> int:
    """Fit every response and optimise on its interval end or POE; print or write the result."""
    from ..io import InputError
    from ..model import fit
    from ..optimize.robust import optimize_robust, parse_interval, parse_robust_goal
    from .errors import about_file, about_response
    from .options import check_distinct_responses, per_response_values, response_options
    from .paths import print_notes, print_summary_or_json, read_input
    from .specs import model_spec, random_effect, random_effect_columns

    responses = list(args.response)
    n = len(responses)
    check_distinct_responses(responses)
    specs = [model_spec(response_options(args, i)) for i in range(n)]
    goals_in = per_response_values(args.goal, n, "--goal")
    intervals = per_response_values(args.interval, n, "--interval")
    weights = per_response_values(args.weight, n, "--weight")
    imps = per_response_values(args.importance, n, "--importance")
    limits = per_response_values(args.limits, n, "--limits")
    goals, poe = [], []
    for r, g, w, i, lim, iv in zip(responses, goals_in, weights, imps, limits, intervals):
        try:
            goal, is_poe = parse_robust_goal(r, g, weight=w, importance=i, limits=lim)
            parse_interval(iv)
        except ValueError as exc:
            option = "--interval" if getattr(exc, "parameter", None) == "interval" else "--goal"
            raise InputError(f"{option}: {exc}") from None
        goals.append(goal)
        if is_poe:
            poe.append(r)
    data = read_input(args)
    notes: list = []
    with about_file(args.data):
        from ..factors import choose_factors

        choice = None if args.component else choose_factors(
            data, args.factor, exclude=responses + ([args.block] if args.block else []) + random_effect_columns(args))
        fits = {}
        for i, r in enumerate(responses):
            with about_response(r, n > 1):
                fits[r] = fit(data, r, factors=args.factor if choice is None else choice.space, block=args.block,
                              model=specs[i], components=args.component, **random_effect(args))
            notes += [str(x) for x in fits[r].input_notes if choice is None or x not in choice.notes]
        if choice is not None:
            notes = [str(x) for x in choice.notes] + notes
        best = optimize_robust(fits, goals, poe=poe, intervals=dict(zip(responses, intervals)),
                               factor_sd=args.factor_sd, confidence=args.confidence, tolerance=args.tolerance,
                               bounds=args.bound, constraints=args.constraint)
    print_notes(dict.fromkeys(notes))
    print_summary_or_json(args, best, extra={"models": {r: f.label for r, f in fits.items()}})
    return 0
