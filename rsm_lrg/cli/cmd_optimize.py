"""``rsm-lrg optimize``: fit, then minimise, maximise or hit a target inside the factor box."""

from __future__ import annotations

import argparse
import contextlib

from .cmd_fit import add_dispersion_options
from .errors import about_file
from .options import (
    add_block_option,
    add_component_option,
    add_data_response,
    add_factor_options,
    add_force,
    add_goal_options,
    add_json,
    add_model_refinements,
    add_random_effect_options,
    add_region_options,
)
from .robust_optimize import add_robust_options, robust_requested, run_robust
from .specs import random_effect

NAME = "optimize"
HELP = "fit, then find the minimum, maximum or a target inside the factor box"
DESCRIPTION = (
    "Fit the model (as 'rsm-lrg fit') and optimise the fitted response inside the coded box "
    "[-1, 1]^k, or inside tighter --bound NAME=LOW:HIGH limits in actual units (they must lie "
    "inside the factor range). Prints the optimum in actual and coded units with the predicted "
    "value and its 95 % confidence and prediction intervals. The model options are those of "
    "'fit' (--model, --reduce, --alpha-out, --criterion, --transform, --transform-constant); with "
    "several responses, the model options that follow a --response apply to that response only "
    "(given before the first --response they apply to all): --response Y1 --model quadratic "
    "--response Y2 --model linear --transform log. Mixture components (--component NAME[=LOW:HIGH] "
    "with a Scheffé --model) are optimised over the constrained simplex: the blend sums to the total, "
    "each component stays inside its bounds (and --bound), every linear --constraint on the component "
    "names holds, and process factors (--factor) are searched over their box at the same time."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_data_response(parser, several="the response column; repeat (each followed by its --goal and its own model "
                             "options) for a multi-response desirability optimisation")
    add_goal_options(parser, goal_metavar="minimize|maximize|target=V|range", desirability=True,
                     goal_help="what to do with the response before it (default minimize; several listed together after the "
                               "last --response: in --response order)",
                     limits_help="desirability limits per response (multi-response; default: observed min:max)")
    add_factor_options(parser)
    add_component_option(parser)
    add_region_options(parser,
                       bound_help="tighter limits for a factor in actual units, or NAME=LEVEL[,LEVEL...] to hold a "
                            "categoric factor at its level(s) (repeatable)",
                       constraint_help="an inequality on the factors in actual units the optimum must satisfy, e.g. "
                            "\"velocity_m_s**2/acceleration_m_s2 <= stroke_m\" or \"0.5*A + B <= 1.2\" "
                            "(repeatable; with several responses the desirability optimum satisfies them)")
    add_block_option(parser, "optimum for the average block")
    add_random_effect_options(parser)
    add_model_refinements(parser, per_response=True, model=True, gp=True)  # a GP: one response, its defaults
    add_robust_options(parser)
    add_dispersion_options(parser, optimise=True)
    add_json(parser)
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from .options import response_options as options_of

    if any(getattr(options_of(args, i), "model", None) == "gp" for i in range(len(args.response))):
        return _run_gp(args)
    if robust_requested(args):  # --interval, --factor-sd or --goal poe (rsm_lrg/cli/robust_optimize.py)
        if args.dispersion:
            from ..io import InputError

            raise InputError("--dispersion: the modelled spread is not available with --interval, --factor-sd or "
                             "--goal poe yet (give it alone)")
        return run_robust(args)
    from ..model import fit
    from ..optimize import optimize, parse_goal
    from .options import per_response_values, response_options
    from .paths import print_notes, print_summary_or_json, read_input
    from .specs import model_spec

    responses = args.response
    specs = [model_spec(response_options(args, i)) for i in range(len(responses))]  # bad options named first
    if len(responses) > 1 or args.weight or args.importance or args.limits or args.dispersion:
        return _multi(args)
    args.response = responses[0]
    args.goal = per_response_values(args.goal, 1, "--goal")[0] or "minimize"
    parse_goal(args.goal)  # a bad goal fails before any work
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=specs[0],
                     components=args.component, **random_effect(args))
        with _constraint_errors(args.constraint):
            best = optimize(result, goal=args.goal, bounds=args.bound, constraints=args.constraint)
    print_notes(result.input_notes)
    print_summary_or_json(args, best)
    return 0


def _spec(args: argparse.Namespace, i: int):
    """The model of response ``i``: ``"gp"`` (a Gaussian process) or its polynomial ModelSpec."""
    from .options import response_options
    from .specs import model_spec

    opts = response_options(args, i)
    return "gp" if getattr(opts, "model", None) == "gp" else model_spec(opts)


def _run_gp(args: argparse.Namespace) -> int:
    """``--model gp``: one response, fitted by a Gaussian process (matern52 kernel, constant
    trend, nugget as 'fit --model gp' chooses it), optimised through the prediction contract."""
    from ..io import InputError
    from ..model import fit
    from ..optimize import optimize, parse_goal
    from .options import per_response_values, response_options
    from .paths import print_notes, print_summary_or_json, read_input

    for opt, attr in (("--component", "component"), ("--block", "block"), ("--terms", "terms"),
                      ("--no-intercept", "no_intercept"), ("--transform", "transform"), ("--reduce", "reduce"),
                      ("--whole-plot", "whole_plot"), ("--random-block", "random_block"),
                      ("--interval", "interval"), ("--factor-sd", "factor_sd")):
        if getattr(args, attr, None) or any(getattr(response_options(args, i), attr, None)
                                            for i in range(len(args.response))
                                            if getattr(response_options(args, i), "model", None) == "gp"):
            raise InputError(f"{opt}: not available with --model gp (a Gaussian process)")
    if len(args.response) > 1:  # a desirability over the responses, each its own model
        return _multi(args)
    args.response = args.response[0]
    args.goal = per_response_values(args.goal, 1, "--goal")[0] or "minimize"
    if str(args.goal).strip().lower() == "poe":
        raise InputError("--goal poe: not available with --model gp (a Gaussian process)")
    parse_goal(args.goal)
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, model="gp")
        with _constraint_errors(args.constraint):
            best = optimize(result, goal=args.goal, bounds=args.bound, constraints=args.constraint)
    print_notes(result.notes)
    print_summary_or_json(args, best)
    return 0


@contextlib.contextmanager
def _constraint_errors(constraints):
    """An error about the constraints (a bad expression, an empty region, no feasible
    setting inside the bounds: a :class:`~rsm_lrg.errors.ParameterError` for ``constraints``)
    gets the option's name in front: ``--constraint: ...``."""
    from ..errors import ParameterError
    from ..io import InputError

    try:
        yield
    except ParameterError as exc:
        if exc.parameter != "constraints":
            raise
        if constraints:
            raise InputError(f"--constraint: {exc}") from None
        raise ValueError(str(exc)) from None  # no feasible setting inside the bounds: the data's fit


def _multi(args) -> int:
    """Several responses: Derringer-Suich desirability (Stat-Ease conventions)."""
    from ..optimize.desirability import optimize_desirability, parse_response_goal
    from .options import check_distinct_responses, per_response_values
    from .paths import print_notes, print_summary_or_json, read_input

    n = len(args.response)
    check_distinct_responses(args.response)
    goals = per_response_values(args.goal, n, "--goal")
    weights = per_response_values(args.weight, n, "--weight")
    imps = per_response_values(args.importance, n, "--importance")
    limits = per_response_values(args.limits, n, "--limits")
    specs = [parse_response_goal(r, g or "minimize", weight=w, importance=i, limits=lim)
             for r, g, w, i, lim in zip(args.response, goals, weights, imps, limits)]
    data = read_input(args)
    with about_file(args.data):
        from .responses import fit_responses

        fits, notes = fit_responses(args, data, args.response,
                                    [_spec(args, i) for i in range(n)])
        models = {r: f.label for r, f in fits.items()}
        if args.dispersion:  # each response's spread, ln s modelled, minimised beside its own goal
            from .cmd_fit import fit_spread

            for r in list(args.response):
                spread = fit_spread(data, r, fits[r].space, args)
                fits[spread.name] = spread.result
                models[spread.name] = f"ln s {args.dispersion_model} ({len(spread.settings)} replicated settings)"
                specs.append(parse_response_goal(spread.name, "minimize"))
        with _constraint_errors(args.constraint):
            best = optimize_desirability(fits, specs, bounds=args.bound, constraints=args.constraint)
    print_notes(notes)
    print_summary_or_json(args, best, extra={"models": models},
                          header=("Models: " + "; ".join(f"{r} {m}" for r, m in models.items()),))
    return 0
