"""``rsm-lrg suggest``: fit a Gaussian process, then choose the next runs (expected improvement,
a batch by the Kriging Believer) and write them as a design CSV."""

from __future__ import annotations

import argparse

from .errors import about_file
from .gp_fit import add_gp_options, check_gp_options, gp_keywords
from .options import MODEL_ORDERS, add_data_response, add_factor_options, add_force, add_json

NAME = "suggest"
HELP = "fit a Gaussian process (or a polynomial) and choose the next runs; write them as a design CSV"
DESCRIPTION = (
    "Fit a Gaussian process to the runs (as 'rsm-lrg fit --model gp', but its length-scales at most 2 "
    "times each factor's range by default, R DiceKriging km's bound, as the loop's), or with --model "
    "linear, 2fi, quadratic or cubic a polynomial by least squares (its standard error of the mean in "
    "place of the kriging sd), and choose --runs new settings "
    "inside the factor box (--bound, --constraint) by --criterion: ei (expected improvement, the "
    "default; for noisy runs measured from the best predicted mean at the runs), pi (probability of "
    "improvement), lcb (confidence bound, mean -+ 2 sd) or variance (pure exploration; on a polynomial "
    "sequential D-optimal augmentation). A batch is "
    "chosen one setting at a time by the Kriging Believer. The settings are written to -o as a design "
    "CSV that simulate, augment and fit read; the table is printed (or the JSON with --json -)."
)


def _runs(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 1000, got {text!r}") from None
    if not 1 <= v <= 1000:
        raise argparse.ArgumentTypeError(f"expected a whole number from 1 to 1000, got {text!r}")
    return v


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser)
    add_factor_options(parser)
    parser.add_argument("--goal", default="minimize", metavar="minimize|maximize|target=V",
                        help="what the next runs should improve (default minimize)")
    parser.add_argument("--runs", type=_runs, default=1, metavar="Q", help="number of new settings (default 1)")
    parser.add_argument("--model", default="gp", choices=["gp", *MODEL_ORDERS],
                        help="the model: gp (a Gaussian process, the default) or a polynomial by least squares")
    parser.add_argument("--criterion", default="ei", choices=["ei", "pi", "lcb", "variance"],
                        help="acquisition criterion (default ei)")
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LOW:HIGH",
                        help="tighter limits for a factor in actual units (repeatable)")
    parser.add_argument("--constraint", action="append", default=None, metavar="EXPR",
                        help="an inequality on the factors in actual units the new runs must satisfy (repeatable)")
    add_gp_options(parser, loop_bounds=True)
    parser.add_argument("-o", "--output", required=True, metavar="NEXT.csv", help="the design CSV of the new runs")
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, write_output
    from ..model import fit
    from ..optimize.next_runs import suggest
    from .paths import print_notes, read_input

    check_gp_options(args, keep=("seed",))  # --seed seeds the search's samples too
    data = read_input(args)
    with about_file(args.data):
        if args.model == "gp":
            result = fit(data, args.response, factors=args.factor, model="gp", **gp_keywords(args, loop_bounds=True))
        else:
            result = fit(data, args.response, factors=args.factor, model=args.model)
        s = suggest(result, args.goal, args.runs, criterion=args.criterion, bounds=args.bound,
                    constraints=args.constraint, seed=0 if args.seed is None else args.seed)
    write_output(args.output, s.design.csv_text(), force=args.force)
    out = dict(s.to_dict(), model=result.to_dict())
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    print_notes(result.notes)
    if args.json == "-":
        dump_json(out, "-")
    else:
        print(s.summary(), end="")
    return 0
