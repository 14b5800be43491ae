"""``rsm-lrg report``: fit a model and write a self-contained HTML report."""

from __future__ import annotations

import argparse

from ._common import about_file, add_force, add_model_inputs, print_notes

NAME = "report"
HELP = "fit a model and write a self-contained HTML report (ANOVA, diagnostics, surfaces, optimum)"
DESCRIPTION = (
    "Fit a response-surface model and write one HTML file that opens offline: the study "
    "summary, the data, the ANOVA laid out like the paper's Table 5 with significant terms "
    "marked, the fit statistics, coefficients with confidence intervals and VIFs, the equation "
    "in coded and actual units, six diagnostic plots, a 3-D surface and a contour for every "
    "pair of factors, the stationary point and the optimum with its CI and PI."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_inputs(parser)
    parser.add_argument("--goal", default="minimize", metavar="minimize|maximize|target=V",
                        help="goal of the optimum section (default minimize, as in the paper)")
    parser.add_argument("--hold", default="center", choices=["center", "optimum"],
                        help="where the factors off a surface's axes are held (default center)")
    parser.add_argument("--title", default=None, help="page title (default: 'Response surface report: COL')")
    parser.add_argument("-o", "--output", required=True, metavar="PATH.html", help="the HTML file to write")
    add_force(parser)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..io import InputError, read_table
    from ..model import fit
    from ..report import write_report

    out = Path(args.output)
    if out.exists() and not args.force:  # before the fit and the figures
        raise InputError(f"{out}: already exists; use --force to overwrite it")
    from ..optimize import parse_goal

    try:  # a bad --goal is named before any data is read
        parse_goal(args.goal)
    except ValueError as exc:
        raise InputError(f"--goal: {exc}") from None
    data = read_table(args.data)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=args.model)
        path = write_report(result, out, force=args.force, title=args.title, source_name=str(args.data),
                            goal=args.goal, hold=args.hold)
    print_notes(result.input_notes)  # the report shows them too
    print(f"wrote {path}")
    return 0
