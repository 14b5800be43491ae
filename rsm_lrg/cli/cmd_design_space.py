"""``rsm-lrg design-space``: where every response stays inside its specification with a
given probability, and the largest operating window (:mod:`rsm_lrg.optimize.design_space`)."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    ResponseGroup,
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
    parser.add_argument("data", metavar="DATA.csv", nargs="?", default=None,
                        help="the runs, one row each (not with --surrogate)")
    add_reader_options(parser)
    parser.add_argument("--response", action=ResponseGroup, metavar="COL", default=None,
                        help="a response column (repeatable, each followed by its own model options; required "
                             "without --surrogate)")
    parser.add_argument("--spec", action="append", required=True, metavar="Y=LOW:HIGH",
                        help="the specification of a response in its units (repeatable; Y=:HIGH or Y=LOW: for one "
                             "side)")
    parser.add_argument("--probability", type=number(0, 1, above=True, below=True), default=0.9, metavar="P",
                        help="the target probability of meeting every specification (default 0.9)")
    parser.add_argument("--grid", type=whole_number(2, 201), default=None, metavar="G",
                        help="grid levels per numeric factor (default 11; 3 to 201; with --surrogate default 5, "
                             "2 to 21)")
    parser.add_argument("--factor-sd", action="append", default=None, metavar="NAME=SD",
                        help="run-to-run standard deviation of a numeric factor in actual units (repeatable)")
    parser.add_argument("--draws", type=whole_number(1, 100000), default=None, metavar="M",
                        help="draws of the factor noise per setting, with --factor-sd (default 1000); with "
                             "--surrogate the surrogate's runs per setting (default 200, at least 4)")
    parser.add_argument("--seed", type=whole_number(0, 2 ** 32 - 1), default=0, metavar="S",
                        help="seed of the factor-noise draws, or of every draw and the run noise with --surrogate "
                             "(default 0)")
    sur = parser.add_argument_group("through the physics (--surrogate)")
    sur.add_argument("--surrogate", action="store_true",
                     help="run the calibrated surrogate itself instead of fitting data: --factor NAME=LOW:HIGH "
                          "(thickness_m, stroke_m, velocity_m_s, acceleration_m_s2; the others at Table 3's centre), "
                          "--spec on its outputs (tcr_c_per_min=:0.035); the calibrated parameters are drawn from "
                          "their intervals (one known only by a bound uniformly over its range), and the variance "
                          "of each setting is attributed to the parameters, the tolerances and the run noise")
    sur.add_argument("--param-sd", action="append", default=None, metavar="NAME=SD",
                     help="a tolerance of the rig with --surrogate: a design factor (thickness_m=5e-6, the leaf "
                          "thickness) or a physical parameter (preload_n=5) varied by a normal deviation with this SD "
                          "(repeatable)")
    sur.add_argument("--calibration", default=None, metavar="PATH",
                     help="with --surrogate: the calibration TOML (default: the shipped data/calibration.toml)")
    sur.add_argument("--workers", type=whole_number(1, 64), default=1, metavar="K",
                     help="with --surrogate: local worker processes for the runs (the numbers do not depend on it)")
    sur.add_argument("--no-attribution", action="store_true",
                     help="with --surrogate: skip the variance attribution (one run per draw instead of five)")
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LEVEL",
                        help="hold a categoric factor at a level (default: its first level)")
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser, "probability for the average block")
    add_random_effect_options(parser)
    add_model_refinements(parser, per_response=True, model=True)
    parser.add_argument("-o", "--output", default=None, metavar="PAGE.html",
                        help="also write the page of probability maps and the window (with --surrogate also the variance "
                             "attribution per setting)")
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


def _specs(items: list[str], responses: list[str] | None) -> dict[str, tuple[float | None, float | None]]:
    """``--spec Y=LOW:HIGH`` (repeatable) as ``{Y: (low, high)}`` (an open side None); each
    name once and, with ``responses``, one of them."""
    from ..errors import ParameterError
    from ..io import InputError, quote_user_value
    from ..optimize.design_space import parse_spec
    from .errors import option_error

    specs: dict[str, tuple[float | None, float | None]] = {}
    for text in items:
        try:
            name, lo, hi = parse_spec(text)
        except (ParameterError, ValueError) as exc:
            raise option_error(exc) from None
        if responses is not None and name not in responses:
            raise InputError(f"--spec: {quote_user_value(name)} is not a --response ({', '.join(responses)})")
        if name in specs:
            raise InputError(f"--spec: {quote_user_value(name)} is given twice")
        specs[name] = (lo, hi)
    return specs


def _numbers(items: list[str] | None, option: str) -> dict[str, float]:
    """``NAME=NUMBER`` pairs of ``option`` (``--factor-sd``, ``--param-sd``) as floats."""
    from ..io import InputError, quote_user_value

    out: dict[str, float] = {}
    for name, value in _pairs(items, option).items():
        try:
            out[name] = float(value)
        except ValueError:
            raise InputError(f"{option}: {quote_user_value(name)}: expected a number, got "
                             f"{quote_user_value(value)}") from None
    return out


def run(args: argparse.Namespace) -> int:
    from ..io import InputError
    from ..optimize.design_space import design_space
    from .options import check_distinct_responses, response_options
    from .paths import print_notes, print_summary_or_json, read_input
    from .responses import fit_responses
    from .specs import model_spec

    if args.surrogate:
        return _run_surrogate(args)
    if args.data is None:
        raise InputError("DATA.csv: give the data file (or --surrogate to run the physics)")
    if not args.response:
        raise InputError("--response: give the response column(s) to fit (required without --surrogate)")
    for option in ("param_sd", "calibration"):
        if getattr(args, option):
            raise InputError(f"--{option.replace('_', '-')}: only with --surrogate")
    if args.workers != 1 or args.no_attribution:
        raise InputError(f"{'--workers' if args.workers != 1 else '--no-attribution'}: only with --surrogate")
    args.grid = 11 if args.grid is None else args.grid
    if args.grid < 3:
        raise InputError(f"--grid {args.grid}: at least 3 levels")
    args.draws = 1000 if args.draws is None else args.draws
    responses = list(args.response)
    check_distinct_responses(responses)
    specs = _specs(args.spec, responses)
    sds = _numbers(args.factor_sd, "--factor-sd")
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


def _run_surrogate(args: argparse.Namespace) -> int:
    """``design-space --surrogate`` (:mod:`rsm_lrg.paper.surrogate_space`)."""
    from ..io import InputError, quote_user_value
    from .errors import option_error
    from .paths import print_summary_or_json

    given = [o for o, v in (("DATA.csv", args.data), ("--response", args.response), ("--factor-sd", args.factor_sd),
                            ("--component", args.component), ("--bound", args.bound), ("--block", args.block))
             if v]
    if given:
        raise InputError(f"{given[0]}: not with --surrogate (the surrogate is run, not fitted; tolerances are "
                         "--param-sd)")
    factors: dict[str, tuple[float, float]] = {}
    for text in args.factor or []:
        name, sep, rest = str(text).partition("=")
        lo_t, colon, hi_t = rest.partition(":")
        try:
            lo, hi = float(lo_t), float(hi_t)
        except ValueError:
            lo = hi = float("nan")
        if not sep or not colon or not (lo == lo and hi == hi):
            raise InputError(f"--factor: expected NAME=LOW:HIGH with --surrogate, got {quote_user_value(text)}")
        if name.strip() in factors:
            raise InputError(f"--factor: {quote_user_value(name.strip())} is given twice")
        factors[name.strip()] = (lo, hi)
    specs = _specs(args.spec, None)
    sds = _numbers(args.param_sd, "--param-sd")
    calibration: object = "default"
    if args.calibration:
        from ..surrogate.calibrate import load_calibration

        try:
            calibration = load_calibration(args.calibration)
        except (OSError, ValueError) as exc:
            raise InputError(f"--calibration {quote_user_value(args.calibration)}: {exc}") from None
    from ..paper.surrogate_space import surrogate_design_space

    try:
        result = surrogate_design_space(factors, specs, probability=args.probability,
                                        grid=5 if args.grid is None else args.grid,
                                        draws=200 if args.draws is None else args.draws, seed=args.seed,
                                        calibration=calibration, param_sd=sds or None, workers=args.workers,
                                        attribution=not args.no_attribution)
    except ValueError as exc:
        if getattr(exc, "parameter", None) is None:
            raise
        raise option_error(exc, options={"factors": "--factor", "param_sd": "--param-sd"}) from None
    if args.output:
        from ..report.design_space_page import write_design_space_page

        write_design_space_page(result.space, args.output, force=args.force, source_name="the calibrated surrogate",
                                attribution=result.nodes)
    args.data = f"the calibrated surrogate ({args.calibration or 'data/calibration.toml'})"
    print_summary_or_json(args, result)
    return 0
