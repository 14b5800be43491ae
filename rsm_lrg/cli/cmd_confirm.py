"""``rsm-lrg confirm``: confirmation runs against the prediction interval."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    FIT_MODELS,
    add_block_option,
    add_component_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_json,
    add_model_option,
    add_model_refinements,
    add_random_effect_options,
    check_at_settings,
)

NAME = "confirm"
HELP = "check confirmation runs against the prediction interval for their mean"
DESCRIPTION = (
    "Fit the model, predict at the --at settings (actual units) and compare the mean of the "
    "--observed confirmation runs with the 95 % prediction interval for the mean of that many "
    "runs: inside or outside, and the relative error against the prediction (and against "
    "--reference, e.g. a rounded published prediction). The model options are those of 'fit': "
    "--reduce (with --alpha-out, --criterion) confirms the reduced model, --transform computes "
    "the interval on the transformed scale and back-transforms it (as Design-Expert does)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser)
    from .options import number, probability

    parser.add_argument("--at", action="extend", nargs="+", required=True, metavar="NAME=VALUE",
                        help="a factor setting in actual units, one for every factor: --at A=1 --at B=2 "
                             "(several after one --at work too: --at A=1 B=2)")
    parser.add_argument("--observed", type=number(), nargs="+", required=True, metavar="V",
                        help="the confirmation run result(s)")
    parser.add_argument("--reference", type=number(), default=None, metavar="V",
                        help="also give the relative error against this value")
    parser.add_argument("--confidence", type=probability, default=0.95, metavar="C",
                        help="interval level (default 0.95)")
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser, "prediction for the average block")
    add_random_effect_options(parser)
    add_model_option(parser, FIT_MODELS, default=None)
    add_model_refinements(parser)
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from ..model import fit
    from ..optimize.confirm import confirm
    from .paths import print_notes, print_summary_or_json, read_input
    from .specs import model_spec, random_effect

    check_at_settings(args.at)
    spec = model_spec(args)
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=spec,
                     components=args.component, **random_effect(args))
    extra = {"reduction": result.reduction.to_dict()} if result.reduction is not None else {}
    try:  # the settings are an option: an error names --at, not the data file
        from ..optimize.confirm import parse_settings

        settings = parse_settings(result.space, args.at)
        result.predict({k: [v] for k, v in settings.items()})  # e.g. a blend off the total: --at's fault
    except ValueError as exc:
        from ..io import InputError

        raise InputError(f"--at: {exc}") from None
    with about_file(args.data):
        c = confirm(result, settings, args.observed, confidence=args.confidence, reference=args.reference)
    print_notes(result.input_notes)
    label = result.label
    header = (f"Model: {label}",) if args.reduce or args.transform is not None or args.terms else ()
    print_summary_or_json(args, c, extra={"model": label, **extra}, header=header)
    return 0
