"""``rsm-lrg evaluate``: evaluate a design before any data (VIF, leverage, prediction variance, FDS, power)."""

from __future__ import annotations

import argparse

from ._common import about_file, add_force, add_json, add_model_option

NAME = "evaluate"
HELP = "evaluate a design for a model before any data: VIF, leverage, prediction variance, FDS, power"
DESCRIPTION = (
    "Read a design CSV (as written by 'rsm-lrg design') and report, for the chosen model, the "
    "degrees of freedom, each term's standard error (in units of sigma), VIF and power to "
    "detect a 2-sigma effect at alpha 0.05, the leverage of every run, the scaled prediction "
    "variance at the centre, at the design points and over the region (its maximum by an exact "
    "search of every face, edge and vertex of the cube), the G-efficiency and the "
    "fraction-of-design-space curve. A model the design cannot estimate is refused (exit 2) "
    "with the aliased terms named. A data CSV without coded columns is read as well: its "
    "numeric columns (minus --exclude) are the factors, coded from their observed range."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("design", metavar="DESIGN.csv", help="the design")
    add_model_option(parser, what="model to evaluate")
    parser.add_argument("--region", default="cube", choices=["cube", "sphere"],
                        help="region for the prediction variance (default: the coded cube)")
    from ._common import number, probability

    parser.add_argument("--alpha", type=probability, default=0.05, metavar="A",
                        help="level of the power test (default 0.05)")
    parser.add_argument("--effect", type=number(0, 1e6, above=True), default=2.0, metavar="SD",
                        help="effect to detect, in standard deviations (default 2)")
    parser.add_argument("--exclude", action="append", default=[], metavar="COL",
                        help="a column that is not a factor (data CSVs only; repeatable)")
    add_json(parser)
    add_force(parser)


def _load(path, exclude):
    from ..design import read_design
    from ..design.core import Design
    from ..factors import FactorSpace
    from ..io import read_table

    df = read_table(path)
    for col in exclude or []:  # nothing is guessed: a column that is not there is an error
        if col not in df.columns:
            from ..io import InputError, quote_user_value

            raise InputError(f"--exclude {quote_user_value(col)}: no such column in {path} "
                             f"(columns: {', '.join(map(str, df.columns))})")
    if any(str(c).lower().startswith("coded_") for c in df.columns):
        return read_design(path)
    space = FactorSpace.from_data(df, None, exclude=exclude)
    coded = space.encode(df).to_numpy(dtype=float)
    n = len(df)
    import numpy as np

    return Design(space, "custom", coded, np.arange(1, n + 1), np.arange(1, n + 1))


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json
    from ..model.evaluate import evaluate_design

    with about_file(args.design):
        design = _load(args.design, args.exclude)
        ev = evaluate_design(design, args.model, region=args.region, alpha=args.alpha, effect_sd=args.effect)
        if not ev.estimable:  # a clear refusal naming the aliased terms (exit 2), never negative df
            raise ValueError(ev.not_estimable_message())
    if args.json and args.json != "-":
        dump_json(ev.to_dict(), args.json, force=args.force)
    if args.json == "-":
        dump_json(ev.to_dict(), "-")
    else:
        print(f"Design: {args.design}")
        print(ev.summary(), end="")
    return 0
