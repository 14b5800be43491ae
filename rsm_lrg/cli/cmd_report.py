"""``rsm-lrg report``: fit one or several responses and write a self-contained HTML report."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    add_block_option,
    add_component_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_goal_options,
    add_model_refinements,
    add_random_effect_options,
    add_region_options,
)
from .paths import print_notes

NAME = "report"
HELP = "fit one or several responses and write a self-contained HTML report (profiler, overlay, ANOVA, diagnostics)"
DESCRIPTION = (
    "Fit response-surface models and write one HTML file that opens offline. By default the page "
    "is interactive: a prediction profiler (a slider per factor, a level picker per categoric "
    "factor; each response's prediction with its 95 % CI and PI, computed in the page from the "
    "fitted models), an overlay (sweet-spot) plot with editable limits, rotatable 3-D surfaces and "
    "contours that follow the profiler, buttons that jump to each optimum and to the desirability "
    "optimum, and the setting as --at options for `rsm-lrg confirm`; then, per response, the "
    "ANOVA laid out like the paper's Table 5, fit statistics, coefficients, equations, diagnostics "
    "and the optimum. --static writes the page without scripts, with a static 3-D surface and "
    "contour for every pair of factors (one response: the page of earlier versions). Several "
    "responses: repeat --response; the model options that follow a --response apply to it only "
    "(--response Y1 --reduce --response Y2 --transform log)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser, several="a response column; repeat for several responses in one page, each followed "
                             "by its own model options")
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser)
    add_random_effect_options(parser)
    add_model_refinements(parser, per_response=True, model=True, gp=True)  # a GP: one response, its defaults
    add_goal_options(parser,
                     goal_help="goal of the response it follows (several listed together: in --response order; "
                               "default minimize, as in the paper)",
                     limits_help="overlay and desirability limits of the response it follows (several listed together: in "
                                 "--response order; default: "
                                 "minimize: at most the observed median, maximize: at least the median, else the "
                                 "observed range; either end may be left empty: :0.03)")
    add_region_options(parser,
                       bound_help="as on optimize: tighter limits for a factor in actual units, or NAME=LEVEL[,LEVEL...] "
                            "for a categoric factor (repeatable); the optima, the overlay's shading and the setting "
                            "deepest inside every limit stay inside them",
                       constraint_help="as on optimize: an inequality on the factors in actual units, e.g. "
                            "\"velocity_m_s**2/acceleration_m_s2 <= stroke_m\" (repeatable); the optima, the overlay's "
                            "shading and the setting deepest inside every limit stay inside it")
    parser.add_argument("--hold", default="center", choices=["center", "optimum"],
                        help="where the factors off a surface's axes are held, and where the profiler starts "
                             "(default center)")
    parser.add_argument("--static", action="store_true",
                        help="a page without scripts: static figures (a 3-D surface and a contour per pair)")
    parser.add_argument("--title", default=None, help="page title (default: the responses' names)")
    parser.add_argument("-o", "--output", required=True, metavar="PATH.html", help="the HTML file to write")
    add_force(parser)


def _limits(text, response: str):
    if text is None:
        return None
    lo, sep, hi = str(text).partition(":")
    try:
        out = (float(lo) if lo.strip() else None, float(hi) if hi.strip() else None)
    except ValueError:
        out = None
    if not sep or out is None:
        from ..io import InputError

        raise InputError(f"--limits {text!r} (response {response!r}): expected LOW:HIGH")
    return out


def _region(space, constraints, bounds):
    """The page's region (:func:`rsm_lrg.report.region.region_data`) of ``--constraint`` and
    the numeric ``--bound`` options, each error naming its option."""
    from ..factors import parse_factor_spec
    from ..io import InputError
    from ..report.region import region_data

    numeric = {}
    for text in bounds or []:
        if "=" in text and ":" not in text.split("=", 1)[1]:  # NAME=LEVEL[,LEVEL]: a categoric factor held
            continue
        try:
            name, lo, hi = parse_factor_spec(text)
        except ValueError as exc:
            raise InputError(f"--bound: {exc}") from None
        if lo is None or hi is None:
            raise InputError(f"--bound: bound {text!r}: expected NAME=LOW:HIGH")
        try:
            f = space[name]
        except KeyError:
            raise InputError(f"--bound: bound for {name!r}: no such factor (factors: {', '.join(space.names)})") from None
        if not float(lo) < float(hi):
            raise InputError(f"--bound: bound for {f.name!r}: LOW must be below HIGH (got {lo:g} >= {hi:g})")
        numeric[f.name] = (lo, hi)
    try:
        return region_data(space, constraints, numeric)
    except ValueError as exc:
        raise InputError(f"--constraint: {exc}") from None


def _gp_spec(args: argparse.Namespace, opts: argparse.Namespace) -> str:
    """``--model gp`` for a response: the model ``"gp"`` (a Gaussian process with the defaults
    of 'fit --model gp'); the polynomial refinements and blocks are refused, naming the option."""
    from ..io import InputError

    for opt, attr in (("--component", "component"), ("--block", "block"), ("--terms", "terms"),
                      ("--no-intercept", "no_intercept"), ("--transform", "transform"), ("--reduce", "reduce"),
                      ("--whole-plot", "whole_plot"), ("--random-block", "random_block")):
        if getattr(args, attr, None) or getattr(opts, attr, None):
            raise InputError(f"{opt}: not available with --model gp (a Gaussian process)")
    return "gp"


def _gp_against_polynomials(data, fits: dict, specs: list, responses: list, notes: list) -> dict:
    """Per response fitted by a GP: the polynomial orders' PRESS beside its leave-one-out on the
    same runs (the page's table); where no polynomial can be fitted to the runs, a note says why."""
    from ..model.choice.loo_compare import compare_with_polynomials

    out = {}
    for r, spec in zip(responses, specs):
        if spec != "gp":
            continue
        try:
            out[r] = compare_with_polynomials(data, fits[r])
        except ValueError as exc:
            notes.append(f"{r}: no leave-one-out comparison with the polynomials: {exc}")
    return out


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..io import InputError, check_output
    from .options import check_distinct_responses, per_response_values, response_options
    from .paths import read_input
    from .specs import model_spec

    out = Path(args.output)
    check_output(out, force=args.force, option="-o/--output")  # before the fit and the figures
    from ..optimize import parse_goal

    responses = list(args.response)
    n = len(responses)
    check_distinct_responses(responses)
    goals = [g or "minimize" for g in per_response_values(args.goal, n, "--goal")]
    for g in goals:
        try:  # a bad --goal is named before any data is read
            parse_goal(g)
        except ValueError as exc:
            raise InputError(f"--goal: {exc}") from None
    limits = [_limits(t, r) for t, r in zip(per_response_values(args.limits, n, "--limits"), responses)]
    if not args.static:
        from ..report.interactive import plotly_js

        try:  # before any work: the interactive page inlines plotly.js
            plotly_js()
        except ImportError as exc:
            raise InputError(str(exc)) from None
    specs = [_gp_spec(args, response_options(args, i)) if getattr(response_options(args, i), "model", None) == "gp"
             else model_spec(response_options(args, i)) for i in range(n)]  # bad model options named first
    data = read_input(args)
    with about_file(args.data):
        from .responses import fit_responses

        fits, notes = fit_responses(args, data, responses, specs)
        # the optima are found here (the optimise layer); the report only presents them
        from ..optimize.study import report_optima

        region = _region(fits[responses[0]].space, args.constraint, args.bound)
        optima = report_optima(fits, dict(zip(responses, goals)), dict(zip(responses, limits)),
                               bounds=args.bound, constraints=args.constraint)
        for r in responses:  # inside a region, a missing optimum is an error that names the option
            if r in optima.missing and (args.constraint or args.bound):
                raise InputError(f"{'--constraint' if args.constraint else '--bound'}: no optimum of {r}: "
                                 f"{optima.missing[r]}")
        if args.static and n == 1 and fits[responses[0]].transform.identity and hasattr(fits[responses[0]], "anova"):
            from ..report import write_report

            best = optima.single.get(responses[0])
            if best is None:  # the one-response report needs its optimum: say why there is none
                raise InputError(f"--goal {goals[0]}: {optima.missing.get(responses[0], 'no optimum')}")
            path = write_report(fits[responses[0]], out, force=args.force, title=args.title,
                                source_name=str(args.data), goal=goals[0], hold=args.hold, optimum=best)
        else:
            from ..report.interactive import write_interactive_report

            loo = _gp_against_polynomials(data, fits, specs, responses, notes)
            path = write_interactive_report(fits, out, force=args.force, title=args.title, goals=goals,
                                            limits=limits, source_name=str(args.data), start=args.hold,
                                            static=args.static, optima=optima, region=region, loo=loo)
    print_notes(notes)  # the report shows them too
    print(f"wrote {path}")
    return 0
