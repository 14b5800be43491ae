"""``rsm-lrg design-space``: where every response stays inside its specification with a
given probability, and the largest operating window (:mod:`rsm_lrg.optimize.design_space`)."""

from __future__ import annotations

import argparse

from ._common import (
    ResponseGroup,
    about_file,
    add_block_option,
    add_component_option,
    add_factor_options,
    add_force,
    add_json,
    add_model_refinements,
    add_random_effect_options,
    add_reader_options,
    number,
    whole_number,
)

NAME = "design-space"
HELP = "probability of meeting every specification over the factors, and the largest operating window"
DESCRIPTION = (
    "Fit each response (model options as on 'fit'; after a --response they apply to it alone) and "
    "compute, at every node of a grid over the numeric factors, the probability that a new run meets "
    "every --spec Y=LOW:HIGH (either side may be empty): the posterior predictive probability of each "
    "fitted model (its coefficients' uncertainty and the run-to-run noise), responses taken as "
    "independent; with --factor-sd the settings also vary from run to run. Prints the most probable "
    "setting and the largest operating window found (a box of grid nodes at each of which the "
    "probability is at least --probability, that cannot grow by one grid step on any face); -o writes "
    "a page with the probability map over each pair of factors. For a mixture (--component with a "
    "Scheffé --model) the grid is the simplex lattice of the constrained region and the window is "
    "bounds per component with the total kept (the part of the simplex inside them)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each")
    add_reader_options(parser)
    parser.add_argument("--response", required=True, action=ResponseGroup, metavar="COL",
                        help="a response column (repeatable, each followed by its own model options)")
    parser.add_argument("--spec", action="append", required=True, metavar="Y=LOW:HIGH",
                        help="the specification of a response in its units (repeatable; Y=:HIGH or Y=LOW: for one "
                             "side)")
    parser.add_argument("--probability", type=number(0, 1, above=True, below=True), default=0.9, metavar="P",
                        help="the target probability of meeting every specification (default 0.9)")
    parser.add_argument("--grid", type=whole_number(3, 201), default=11, metavar="G",
                        help="grid levels per numeric factor (default 11)")
    parser.add_argument("--factor-sd", action="append", default=None, metavar="NAME=SD",
                        help="run-to-run standard deviation of a numeric factor in actual units (repeatable)")
    parser.add_argument("--draws", type=whole_number(1, 100000), default=1000, metavar="M",
                        help="draws of the factor noise per setting, with --factor-sd (default 1000)")
    parser.add_argument("--seed", type=whole_number(0, 2 ** 32 - 1), default=0, metavar="S",
                        help="seed of the factor-noise draws (default 0)")
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LEVEL",
                        help="hold a categoric factor at a level (default: its first level)")
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser, "probability for the average block")
    add_random_effect_options(parser)
    add_model_refinements(parser, per_response=True, model=True)
    parser.add_argument("-o", "--output", default=None, metavar="PAGE.html",
                        help="also write the page of probability maps and the window")
    add_json(parser)
    add_force(parser)


def _pairs(items: list[str] | None, option: str) -> dict[str, str]:
    from ..io import InputError, quote_user_value

    out: dict[str, str] = {}
    for text in items or []:
        name, sep, value = str(text).partition("=")
        if not sep or not name.strip() or not value.strip():
            raise InputError(f"{option}: expected NAME=VALUE, got {quote_user_value(text)}")
        if name.strip() in out:
            raise InputError(f"{option}: {quote_user_value(name.strip())} is given twice")
        out[name.strip()] = value.strip()
    return out


def run(args: argparse.Namespace) -> int:
    from ..errors import ParameterError
    from ..io import InputError, quote_user_value
    from ..optimize.design_space import design_space, parse_spec
    from ._common import (
        check_distinct_responses,
        model_spec,
        option_error,
        print_notes,
        print_summary_or_json,
        read_input,
        response_options,
    )
    from .responses import fit_responses

    responses = list(args.response)
    check_distinct_responses(responses)
    specs: dict = {}
    for text in args.spec:
        try:
            name, lo, hi = parse_spec(text)
        except ParameterError as exc:
            raise option_error(exc) from None
        if name not in responses:
            raise InputError(f"--spec: {quote_user_value(name)} is not a --response ({', '.join(responses)})")
        if name in specs:
            raise InputError(f"--spec: {quote_user_value(name)} is given twice")
        specs[name] = (lo, hi)
    sds: dict[str, float] = {}
    for name, value in _pairs(args.factor_sd, "--factor-sd").items():
        try:
            sds[name] = float(value)
        except ValueError:
            raise InputError(f"--factor-sd: {quote_user_value(name)}: expected a number, got "
                             f"{quote_user_value(value)}") from None
    held = _pairs(args.bound, "--bound")
    specs_models = [model_spec(response_options(args, i)) for i in range(len(responses))]
    data = read_input(args)
    with about_file(args.data):
        fits, notes = fit_responses(args, data, responses, specs_models)
        ds = design_space(fits, specs, probability=args.probability, grid=args.grid, factor_sd=sds or None,
                          draws=args.draws, seed=args.seed, held=held)
    if args.output:
        from ..report.design_space_page import write_design_space_page

        write_design_space_page(ds, args.output, force=args.force, source_name=str(args.data))
    print_notes(notes)
    print_summary_or_json(args, ds, extra={"models": {r: f.label for r, f in fits.items()}})
    return 0
