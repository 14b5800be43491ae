"""``rsm-lrg fit``: fit a response-surface model, print the ANOVA (Table 5 layout) and equation."""

from __future__ import annotations

import argparse

from ._common import about_file, add_factor_options, add_force, add_json

NAME = "fit"
HELP = "fit a response-surface model; print the ANOVA, statistics and equation"
DESCRIPTION = (
    "Fit a linear, 2FI or quadratic model by least squares in coded units and print the "
    "Design-Expert style ANOVA (partial sums of squares, lack of fit, pure error), the fit "
    "statistics, the coefficients, the equation in coded and actual terms and the canonical "
    "analysis. With --json - the JSON goes to standard output instead of the text."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each")
    parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    add_factor_options(parser)
    parser.add_argument("--block", metavar="COL", default=None, help="block column (effects sum to zero)")
    parser.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                        help="model order (default quadratic)")
    add_json(parser)
    parser.add_argument("--report", metavar="PATH", default=None, help="also write a self-contained HTML report")
    add_force(parser)


def _write_report(result, path, force: bool) -> None:
    import importlib

    try:
        mod = importlib.import_module("rsm_lrg.report")
    except ImportError:
        mod = None
    writer = getattr(mod, "write_report", None) if mod is not None else None
    if writer is None:
        raise ValueError(f"{path}: --report is not available yet in this version (no HTML report writer)")
    writer(result, path, force=force)


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, read_table
    from ..model import fit

    data = read_table(args.data)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=args.model)
    if args.json and args.json != "-":
        dump_json(result.to_dict(), args.json, force=args.force)
    if args.report:
        _write_report(result, args.report, args.force)
    if args.json == "-":
        dump_json(result.to_dict(), "-")
    else:
        print(f"Data: {args.data}")
        print(result.summary(), end="")
    return 0
