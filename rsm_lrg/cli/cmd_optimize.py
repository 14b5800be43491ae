"""``rsm-lrg optimize``: fit, then minimise, maximise or hit a target inside the factor box."""

from __future__ import annotations

import argparse

from ._common import about_file, add_factor_options, add_force, add_json

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
    parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    parser.add_argument("--goal", default="minimize", metavar="minimize|maximize|target=V",
                        help="what to do with the response (default minimize)")
    add_factor_options(parser)
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LOW:HIGH",
                        help="tighter limits for a factor in actual units (repeatable)")
    parser.add_argument("--block", metavar="COL", default=None, help="block column (optimum for the average block)")
    parser.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                        help="model order (default quadratic)")
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, read_table
    from ..model import fit
    from ..optimize import optimize, parse_goal

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
