"""``rsm-lrg ridge``: ridge path (second-order model) or steepest path (first order)."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    MODEL_ORDERS,
    add_block_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_json,
    add_model_option,
)
from .paths import print_notes, print_summary_or_json

NAME = "ridge"
HELP = "ridge analysis (second order) or path of steepest ascent/descent (first order)"
DESCRIPTION = (
    "Fit the model, then follow the path of best predicted response away from the design "
    "centre: for a second-order model the ridge path (the best point on each sphere of "
    "radius r, R rsm's steepest()), for a first-order model the straight path of steepest "
    "ascent or descent. Points at every multiple of --step up to --radius (coded units), in "
    "coded and actual units with the predicted response."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser)
    parser.add_argument("--goal", default="maximize", choices=["maximize", "minimize"],
                        help="ascent (maximize, default) or descent (minimize)")
    from .options import number

    parser.add_argument("--radius", type=number(0, 1e6), default=None, metavar="R",
                        help="largest distance from the centre in coded units (default: the farthest design point)")
    parser.add_argument("--step", type=number(0, above=True), default=0.1, metavar="S", help="spacing of the path points (default 0.1)")
    add_factor_options(parser)
    add_block_option(parser, "path for the average block")
    add_model_option(parser, MODEL_ORDERS[:3])
    from .options import add_terms_options

    add_terms_options(parser)
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..model import fit
    from ..model.readings.ridge import radii, ridge
    from .paths import read_input
    from .specs import model_spec

    radii(0.0 if args.radius is None else args.radius, args.step)  # bad numbers fail before any work
    spec = model_spec(args)
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=spec)
        path = ridge(result, goal=args.goal, radius=args.radius, step=args.step)
    print_notes(result.input_notes)  # after the work: a failed command prints one error line only
    print_summary_or_json(args, path)
    return 0
