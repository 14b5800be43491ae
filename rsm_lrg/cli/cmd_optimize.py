"""``rsm-lrg optimize``: fit, then minimise, maximise or hit a target inside the factor box."""

from __future__ import annotations

import argparse

from ._common import about_file, add_block_option, add_factor_options, add_force, add_json, add_model_option

NAME = "optimize"
HELP = "fit, then find the minimum, maximum or a target inside the factor box"
DESCRIPTION = (
    "Fit the model (as 'rsm-lrg fit') and optimise the fitted response inside the coded box "
    "[-1, 1]^k, or inside tighter --bound NAME=LOW:HIGH limits in actual units (they must lie "
    "inside the factor range). Prints the optimum in actual and coded units with the predicted "
    "value and its 95 % confidence and prediction intervals."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each")
    parser.add_argument("--response", required=True, action="append", metavar="COL",
                        help="the response column; repeat (each followed by its --goal) for a "
                             "multi-response desirability optimisation")
    parser.add_argument("--goal", action="append", default=None, metavar="minimize|maximize|target=V|range",
                        help="what to do with the response before it (default minimize)")
    parser.add_argument("--weight", action="append", default=None, metavar="W[,W2]",
                        help="desirability weight 0.1..10 per response (multi-response; default 1)")
    parser.add_argument("--importance", action="append", default=None, metavar="R",
                        help="importance 1..5 per response (multi-response; default 3)")
    parser.add_argument("--limits", action="append", default=None, metavar="LOW:HIGH",
                        help="desirability limits per response (multi-response; default: observed min:max)")
    add_factor_options(parser)
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LOW:HIGH",
                        help="tighter limits for a factor in actual units (repeatable)")
    add_block_option(parser, "optimum for the average block")
    add_model_option(parser)
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, read_table
    from ..model import fit
    from ..optimize import optimize, parse_goal

    responses = args.response
    goals = args.goal or []
    if len(responses) > 1 or args.weight or args.importance or args.limits:
        return _multi(args)
    if len(goals) > 1:
        raise ValueError("one --goal per --response")
    args.response = responses[0]
    args.goal = goals[0] if goals else "minimize"
    parse_goal(args.goal)  # a bad goal fails before any work
    data = read_table(args.data)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=args.model)
        best = optimize(result, goal=args.goal, bounds=args.bound)
    if args.json and args.json != "-":
        dump_json(best.to_dict(), args.json, force=args.force)
    if args.json == "-":
        dump_json(best.to_dict(), "-")
    else:
        print(f"Data: {args.data}")
        print(best.summary(), end="")
    return 0


def _per_response(values, n, what):
    values = values or []
    if len(values) > n:
        raise ValueError(f"more --{what} options ({len(values)}) than --response options ({n})")
    return list(values) + [None] * (n - len(values))


def _multi(args) -> int:
    """Several responses: Derringer-Suich desirability (Stat-Ease conventions)."""
    from ..io import dump_json, read_table
    from ..model import fit
    from ..optimize.desirability import optimize_desirability, parse_response_goal

    n = len(args.response)
    if len(set(args.response)) != n:
        raise ValueError("each --response may be given once")
    goals = _per_response(args.goal, n, "goal")
    weights = _per_response(args.weight, n, "weight")
    imps = _per_response(args.importance, n, "importance")
    limits = _per_response(args.limits, n, "limits")
    specs = [parse_response_goal(r, g or "minimize", weight=w, importance=i, limits=lim)
             for r, g, w, i, lim in zip(args.response, goals, weights, imps, limits)]
    data = read_table(args.data)
    with about_file(args.data):
        fits = {}
        for r in args.response:
            factors = args.factor
            if factors is None:  # other responses are not factors
                from ..factors import FactorSpace

                others = [c for c in args.response if c != r]
                exclude = [r] + others + ([args.block] if args.block else [])
                exclude += [c for c in data.columns if str(c).lower().startswith("coded_")]
                factors = FactorSpace.from_data(data, None, exclude=exclude)
            fits[r] = fit(data, r, factors=factors, block=args.block, model=args.model)
        best = optimize_desirability(fits, specs, bounds=args.bound)
    out = best.to_dict()
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.json == "-":
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        print(best.summary(), end="")
    return 0
