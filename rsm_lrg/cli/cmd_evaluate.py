"""``rsm-lrg evaluate``: evaluate a design before any data (VIF, leverage, prediction variance, FDS, power)."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import (
    add_force,
    add_json,
    add_model_option,
    add_plot_option,
    add_reader_options,
    add_where_options,
    plot_format,
)

NAME = "evaluate"
HELP = ("evaluate a design for a model before any data: VIF, leverage, prediction variance, FDS, power, "
        "D/A/G/I efficiency, alias map; compare designs side by side")
DESCRIPTION = (
    "Read a design CSV (as written by 'rsm-lrg design') and report, for the chosen model, the "
    "degrees of freedom, each term's standard error (in units of sigma), VIF and power to "
    "detect a 2-sigma effect at alpha 0.05, the leverage of every run, the scaled prediction "
    "variance at the centre, at the design points and over the region (its maximum by an exact "
    "search of every face, edge and vertex of the cube), the G-efficiency and the "
    "fraction-of-design-space curve, the D-, A- and G-efficiencies and the average prediction "
    "variance I, and the alias matrix and correlation map of the model and the potential terms "
    "(--potential: the next bigger model by default). Two or more designs are compared side by "
    "side: a table of the criteria (with efficiencies relative to the best design) and the FDS "
    "curves, drawn on one plot with --plot PATH.png|svg. A model the design cannot estimate is refused (exit 2) "
    "with the aliased terms named. A data CSV without coded columns is read as well: its "
    "numeric columns (minus --exclude) are the factors, coded from their observed range. A split-plot "
    "design (a whole_plot column, or --whole-plot COL) is also evaluated under generalised least "
    "squares: D- and A-efficiency and the average prediction variance I from X'V^-1 X with "
    "V = I + eta J per whole plot (--variance-ratio eta, default 1)."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("design", metavar="DESIGN.csv", nargs="+",
                        help="the design; two or more are compared side by side")
    add_reader_options(parser)
    add_model_option(parser, what="model to evaluate")
    from .options import add_terms_options

    add_terms_options(parser)
    parser.add_argument("--region", default="cube", choices=["cube", "sphere"],
                        help="region for the prediction variance (default: the coded cube)")
    from .options import number, probability, whole_number

    parser.add_argument("--alpha", type=probability, default=0.05, metavar="A",
                        help="level of the power test (default 0.05)")
    parser.add_argument("--effect", "--effect-size", dest="effect", type=number(0, 1e6, above=True), default=2.0,
                        metavar="SD", help="effect to detect over the coded range -1..+1 (coefficient SD/2), in "
                                           "standard deviations; with --family binomial on the logit scale (default 2)")
    parser.add_argument("--exclude", action="append", default=[], metavar="COL",
                        help="a column that is not a factor (data CSVs only; repeatable)")
    parser.add_argument("--potential", default="auto", choices=["auto", "none", "2fi", "quadratic", "cubic"],
                        help="model whose extra terms are the potential terms of the alias map (default auto: "
                             "the next bigger model; none: no alias map)")
    parser.add_argument("--whole-plot", default=None, metavar="COL",
                        help="the whole-plot column of a split-plot design (default: the column whole_plot "
                             "when there is one): adds the GLS criteria")
    parser.add_argument("--variance-ratio", type=number(0, 1e6), default=None, metavar="ETA",
                        help="eta = sigma^2 whole plot / sigma^2 of the GLS criteria, 0 to 1e6 (default 1)")
    parser.add_argument("--variance-ratio-of", action="append", default=[], metavar="COL=ETA",
                        help="eta of one random stratum by its group column (whole_plot, subplot, strip_row, "
                             "strip_column), over --variance-ratio (repeatable)")
    power = parser.add_argument_group("power by simulation (--power)")
    power.add_argument("--power", action="store_true",
                       help="report the Monte Carlo power of each coefficient instead of the evaluation: responses "
                            "simulated at --effect-size (noise sigma 1; whole plots with variance eta sigma^2) and "
                            "refitted by the analysis fit runs (OLS t tests, REML with Kenward-Roger for whole plots, "
                            "binomial GLM likelihood-ratio tests), beside the exact OLS power")
    power.add_argument("--family", default=None, choices=["gaussian", "binomial"],
                       help="response family of --power (default gaussian); binomial: one pass/fail per run, "
                            "logit link")
    power.add_argument("--baseline", type=number(), default=None, metavar="P",
                       help="probability at the design centre of a binomial --power simulation, strictly between "
                            "0 and 1 (default 0.5)")
    power.add_argument("--draws", type=whole_number(1, 10_000_000), default=None, metavar="N",
                       help="simulated responses of --power (default 1000)")
    power.add_argument("--seed", type=whole_number(0, 2 ** 63 - 1), default=None, metavar="S",
                       help="seed of --power's draws (default 1); the same seed gives the same numbers for any "
                            "--workers")
    add_where_options(parser, "run --power's blocks of draws", most_workers=64, group=power)
    add_plot_option(parser, "the fraction-of-design-space curve(s) on one plot")
    add_json(parser)
    add_force(parser)


def _load(path, exclude, args):
    from ..design.core import Design, design_of_frame
    from ..factors import FactorSpace
    from .paths import read_input

    df = read_input(args, path)
    for col in exclude or []:  # nothing is guessed: a column that is not there is an error
        if col not in df.columns:
            from ..io import InputError, quote_user_value

            raise InputError(f"--exclude {quote_user_value(col)}: no such column in {path} "
                             f"(columns: {', '.join(map(str, df.columns))})")
    wp = getattr(args, "whole_plot", None)
    if wp is not None and wp not in df.columns:
        from ..io import InputError, quote_user_value

        raise InputError(f"--whole-plot {quote_user_value(wp)}: no such column in {path} "
                         f"(columns: {', '.join(map(str, df.columns))})")
    if any(str(c).lower().startswith("coded_") for c in df.columns):
        return design_of_frame(df, path, whole_plot=wp)
    from ..design.core import WHOLE_PLOT_COLUMN, whole_plot_codes

    if wp is None and WHOLE_PLOT_COLUMN in df.columns:
        wp = WHOLE_PLOT_COLUMN
    from ..design.core import STRATUM_COLUMNS

    groups = [c for c in STRATUM_COLUMNS if c in df.columns]
    space = FactorSpace.from_data(df, None, exclude=list(exclude or []) + ([wp] if wp is not None else []) + groups)
    coded = space.encode(df).to_numpy(dtype=float)
    n = len(df)
    import numpy as np

    plots = None if wp is None else whole_plot_codes(df[wp].tolist(), wp)
    return Design(space, "custom", coded, np.arange(1, n + 1), np.arange(1, n + 1), whole_plots=plots,
                  strata={c: whole_plot_codes(df[c].tolist(), c) for c in groups})


def _stratum_ratios(items: list[str]) -> dict[str, float] | None:
    """``--variance-ratio-of COL=ETA`` as ``{COL: ETA}``; a malformed item is an InputError."""
    import math

    from ..io import InputError, quote_user_value

    out: dict[str, float] = {}
    for item in items:
        col, eq, text = str(item).partition("=")
        try:
            eta = float(text)
        except ValueError:
            eta = math.nan
        if not eq or not col.strip() or not (math.isfinite(eta) and 0 <= eta <= 1e6):
            raise InputError(f"--variance-ratio-of {quote_user_value(item)}: expected COL=ETA with ETA a number "
                             "from 0 to 1e6")
        if col.strip() in out:
            raise InputError(f"--variance-ratio-of {quote_user_value(item)}: {col.strip()} is given twice")
        out[col.strip()] = eta
    return out or None


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, write_output
    from ..model.evaluate import DesignComparison, DesignEvaluation, compare_designs, evaluate_design

    if args.power:
        return _run_power(args)
    for opt in ("family", "baseline", "draws", "seed", "workers", "scheduler"):
        if getattr(args, opt) is not None:
            from ..io import InputError

            raise InputError(f"--{opt}: belongs to --power (power by simulation); give --power too")
    fmt = plot_format(args.plot)
    potential = None if args.potential == "none" else args.potential
    paths = list(args.design)
    if len(set(paths)) != len(paths):
        raise ValueError("each DESIGN.csv may be given once")
    designs = []
    for path in paths:
        with about_file(path):
            designs.append(_load(path, args.exclude, args))
    opts = dict(region=args.region, alpha=args.alpha, effect_sd=args.effect, potential=potential,
                variance_ratio=args.variance_ratio)
    ratios = _stratum_ratios(args.variance_ratio_of)
    if ratios:
        opts["variance_ratios"] = ratios
    result: DesignEvaluation | DesignComparison
    if len(paths) == 1:
        with about_file(paths[0]):
            ev = evaluate_design(designs[0], args.model, terms=args.terms, intercept=not args.no_intercept, **opts)
            if not ev.estimable:  # a clear refusal naming the aliased terms (exit 2), never negative df
                raise ValueError(ev.not_estimable_message())
        result, evs = ev, [ev]
    else:
        comparison = compare_designs(designs, args.model, names=paths, **opts)
        result, evs = comparison, list(comparison.evaluations)
    figure = None
    if fmt is not None:
        from ..report.plots import figure_bytes

        figure = figure_bytes(_fds_figure(evs, paths), fmt)
        write_output(args.plot, figure, force=args.force)
    payload = result.to_dict()  # with the GLS criteria of a split-plot design beside the OLS ones
    if args.json and args.json != "-":
        dump_json(payload, args.json, force=args.force)
    if args.json == "-":
        dump_json(payload, "-")
    else:
        print(f"Design: {paths[0]}" if len(paths) == 1 else "Designs: " + ", ".join(paths))
        print(result.summary(), end="")
    return 0


def _fds_figure(evaluations, names):
    """The FDS curves (unscaled variance against the fraction of the region) on one plot."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(5.0, 3.6))
    fig.subplots_adjust(left=0.15, right=0.97, bottom=0.14, top=0.91)
    ax = fig.add_subplot(1, 1, 1)
    for ev, name in zip(evaluations, names):
        c = ev.fds_curve
        ax.plot(c["fraction"], c["variance"], label=str(name).replace("$", r"\$"), linewidth=1.4)
    ax.set_xlabel("Fraction of design space")
    ax.set_ylabel("Prediction variance x'(X'X)^-1 x [sigma^2]")
    ax.set_title(f"FDS, {evaluations[0].model} model over the {evaluations[0].region}", fontsize=10)
    ax.set_xlim(0.0, 1.0)
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.legend(fontsize=8)
    return fig


def _run_power(args: argparse.Namespace) -> int:
    """``evaluate DESIGN.csv --power``: the Monte Carlo power of every coefficient."""
    from ..io import InputError
    from ..model.power import simulate_power
    from .paths import print_summary_or_json

    if len(args.design) != 1:
        raise InputError("--power: simulates one design at a time; give one DESIGN.csv")
    for opt, given in (("--plot", args.plot is not None), ("--region", args.region != "cube"),
                       ("--potential", args.potential != "auto")):
        if given:
            raise InputError(f"{opt}: not used by --power (power by simulation); leave it out")
    path = args.design[0]
    with about_file(path):
        design = _load(path, args.exclude, args)
    from .processes import cluster_failures, connect_scheduler

    client = None
    if args.scheduler is not None:  # an empty address is refused, not run locally
        client = connect_scheduler(args.scheduler, args.scheduler_timeout)
    try:
        with about_file(path), cluster_failures(args.scheduler, args.workers):
            sim = simulate_power(design, args.model, terms=args.terms, intercept=not args.no_intercept,
                                 effect_sd=args.effect, alpha=args.alpha,
                                 draws=1000 if args.draws is None else args.draws,
                                 seed=1 if args.seed is None else args.seed, family=args.family or "gaussian",
                                 baseline=args.baseline, variance_ratio=args.variance_ratio,
                                 workers=args.workers or 1, executor=None if client is None else client.get_executor())
    finally:
        if client is not None:
            client.close()
    print_summary_or_json(args, sim, source=f"Design: {path}")
    return 0
