"""``rsm-lrg design``: write a design CSV, one sub-command per kind: Box-Behnken, central
composite, full factorial, optimal (D, I, A; on a box, a constrained region or a mixture),
augment, definitive screening, fractional factorial, Plackett-Burman, Latin hypercube, Sobol,
split-plot, split-plot CCD, simplex-lattice, simplex-centroid and extreme vertices."""

from __future__ import annotations

import argparse
from typing import Any

from .errors import about_options, option_error
from .options import add_force, add_reader_options, whole_number

NAME = "design"
HELP = ("write a design CSV (box-behnken, central-composite, full-factorial, optimal, split-plot, split-plot-ccd, "
        "strip-plot, augment, definitive-screening, fractional-factorial, plackett-burman, latin-hypercube, sobol, "
        "simplex-lattice, simplex-centroid, extreme-vertices)")
DESCRIPTION = (
    "Generate an experimental design and write it as CSV: std_order, run_order, block (when "
    "blocked), the coded columns coded_A, coded_B, ... and the actual columns named after the "
    "factors. The run order is randomised from --seed (within blocks) unless --no-randomize."
)


def _order_and_output(p: argparse.ArgumentParser, seed_help: str = "seed of the randomised run order") -> None:
    """What every design kind takes after its own options: ``--seed``, ``--no-randomize``,
    ``-o/--output``, ``--format``/``--response`` and ``--force``."""
    p.add_argument("--seed", type=whole_number(0), default=None, metavar="N",
                   help=f"{seed_help} (default: drawn and printed)")
    p.add_argument("--no-randomize", action="store_true", help="run order = standard order")
    p.add_argument("-o", "--output", required=True, metavar="PATH", help="the design CSV to write")
    add_output_format(p)
    add_force(p)


def _common(p: argparse.ArgumentParser, center_default, center_help: str) -> None:
    p.add_argument("--factor", action="append", required=True, metavar="NAME=LOW:HIGH",
                   help="a factor and the levels coded -1 and +1 (repeat for each factor, in order)")
    p.add_argument("--center", default=center_default, metavar="N", help=center_help)
    _order_and_output(p)


def _base(p: argparse.ArgumentParser, factors: bool = True, constraint: bool = False, required: bool = True) -> None:
    if factors:
        p.add_argument("--factor", action="append", required=required, metavar="SPEC",
                       help="NAME=LOW:HIGH (numeric) or NAME=cat:L1,L2,... (categoric); repeat for each factor"
                            + ("" if required else "; with --component: the process factors of a mixture-process "
                                                   "design"))
    if constraint:
        p.add_argument("--constraint", action="append", default=[], metavar="EXPR",
                       help="an inequality in actual units, e.g. '0.5*A + B <= 1.2' or "
                            "'velocity_m_s**2/acceleration_m_s2 <= stroke_m' (repeatable)")
    _order_and_output(p, seed_help="seed of the search and of the randomised run order")


def add_output_format(p: argparse.ArgumentParser) -> None:
    """``--format csv|xlsx`` and ``--response COL``: the design as a CSV file or as a workbook
    to fill in (a sheet with an empty column per response)."""
    p.add_argument("--format", choices=["csv", "xlsx"], default=None,
                   help="csv or xlsx (a workbook to fill in); default from the output's extension, else csv")
    p.add_argument("--response", action="append", default=None, metavar="COL",
                   help="an empty response column to add (repeatable; default for xlsx: one column 'response')")


def write_design(design, out, args) -> None:
    """Write a new :class:`~rsm_lrg.design.Design` to ``out``: the plain design CSV without
    pandas (:meth:`~rsm_lrg.design.Design.csv_text`), else as :func:`write_design_frame`."""
    from ..io import write_output

    suffix = str(out).lower().rsplit(".", 1)[-1] if "." in str(out) else ""
    if args.format in (None, "csv") and suffix != "xlsx" and not args.response:
        write_output(out, design.csv_text(), force=args.force)
    else:
        write_design_frame(design.to_frame(), out, args)


def write_design_frame(frame, out, args) -> None:
    """Write a design's table to ``out`` as CSV or an ``.xlsx`` workbook (``--format``, or the
    extension), with the ``--response`` columns present and empty."""
    from ..io import InputError, quote_user_value, write_output
    from ..readers import xlsx_bytes

    suffix = str(out).lower().rsplit(".", 1)[-1] if "." in str(out) else ""
    fmt = args.format or ("xlsx" if suffix == "xlsx" else "csv")
    if args.format == "xlsx" and suffix != "xlsx":
        raise InputError(f"--format xlsx: name the output .xlsx (got {quote_user_value(str(out))})")
    if fmt == "csv" and suffix == "xlsx":
        raise InputError(f"--format csv: the output {quote_user_value(str(out))} is named .xlsx")
    responses = args.response if args.response is not None else (
        ["response"] if fmt == "xlsx" and "response" not in frame.columns else [])
    frame = frame.copy()
    for col in responses:
        if col in frame.columns:
            raise InputError(f"--response {quote_user_value(col)}: the design already has a column of that name")
        if not col.strip():
            raise InputError("--response: an empty column name")
        frame[col] = None
    if fmt == "xlsx":
        write_output(out, xlsx_bytes(frame, sheet="Design"), force=args.force)
    else:
        write_output(out, frame.to_csv(index=False, lineterminator="\n"), force=args.force)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="kind", metavar="KIND", required=True)
    op = sub.add_parser("optimal", help="D-, I- or A-optimal design by coordinate exchange",
                        description="Exact optimal design by coordinate exchange (Meyer & Nachtsheim 1995) for "
                                    "numeric and categoric factors, on a box or a constrained region; with "
                                    "--component, a mixture (or mixture-process) design by candidate exchange "
                                    "over the extreme vertices, edge and plane centroids, edge thirds, overall "
                                    "centroid and axial blends of the constrained simplex.")
    _base(op, constraint=True, required=False)
    op.add_argument("--component", action="append", default=None, metavar="NAME[=LOW:HIGH]",
                    help="a mixture component and its bounds in real proportions (bare NAME: 0 to the total); "
                         "repeat for each, in order; --constraint then takes linear inequalities in them")
    op.add_argument("--total", default="1", metavar="T", help="with --component: the total the proportions sum to "
                                                              "(default 1)")
    op.add_argument("--criterion", default=None, type=str.upper, choices=["D", "I", "A"],
                    help="optimality criterion (default I, as Design-Expert; D with --blocks)")
    op.add_argument("--model", default=None,
                    choices=["linear", "2fi", "quadratic", "cubic", "mixture-linear", "mixture-quadratic",
                             "special-cubic", "mixture-cubic"],
                    help="the model the design supports (default quadratic; with --component mixture-quadratic, "
                         "crossed with each process main effect when --factor is given)")
    op.add_argument("--runs", type=whole_number(1), default=None, metavar="N",
                    help="total runs (default: model terms + 5 lack-of-fit points + 5 replicates)")
    op.add_argument("--lof-points", "--lack-of-fit", dest="lof_points", type=whole_number(0, MAX_DESIGN_RUNS),
                    default=None,
                    metavar="L", help="lack-of-fit points spread by distance (default 5 without --runs, else 0)")
    op.add_argument("--replicates", type=whole_number(0, MAX_DESIGN_RUNS), default=None, metavar="R",
                    help="replicated model points (default 5 without --runs, else 0)")
    op.add_argument("--starts", type=whole_number(1, 1000), default=None, metavar="N",
                    help="random starts of the exchange (default by model size)")
    op.add_argument("--blocks", type=whole_number(2, MAX_DESIGN_RUNS), default=None, metavar="N",
                    help="with --component: N blocks (batches, days) as fixed effects; the design is D-optimal for "
                         "the Scheffé model beside the block effects, as fit --block fits them, and the CSV has a "
                         "block column (runs default: terms + N - 1 + 10)")
    op.add_argument("--block-size", default=None, metavar="N[,N...]",
                    help="with --blocks: the runs of every block (one number for all, or one per block; default "
                         "as equal as possible)")
    _split_plot_parser(sub)
    _split_plot_ccd_parser(sub)
    ag = sub.add_parser("augment", help="add runs to a design CSV (optimal, star + centre points, fold-over)",
                        description="Add runs to the runs of DESIGN.csv, which are kept untouched and first, "
                                    "with their responses: D/I/A-optimal runs for a bigger model, star and "
                                    "centre points (a two-level factorial becomes a CCD), or the fold-over.")
    ag.add_argument("design", metavar="DESIGN.csv", help="the design (or data) CSV whose runs are kept")
    add_reader_options(ag)
    ag.add_argument("--method", default="optimal", choices=["optimal", "ccd", "foldover"],
                    help="how to add runs (default optimal)")
    ag.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                    help="optimal: the model the augmented design supports (default quadratic)")
    ag.add_argument("--criterion", default="D", type=str.upper, choices=["D", "I", "A"],
                    help="optimal: criterion of the added runs (default D)")
    ag.add_argument("--runs", type=whole_number(1), default=None, metavar="N", help="optimal: runs to add")
    ag.add_argument("--alpha", default="rotatable", metavar="RULE|X",
                    help="ccd: rotatable (default), face, orthogonal, practical or a number")
    ag.add_argument("--center", type=whole_number(0), default=2, metavar="N", help="ccd: centre points added (default 2)")
    ag.add_argument("--fold", action="append", default=None, metavar="FACTOR",
                    help="foldover: a factor (name or letter) whose signs are reversed (default all; repeatable)")
    ag.add_argument("--new-block", action="store_true", help="put the added runs in a new block")
    ag.add_argument("--constraint", action="append", default=[], metavar="EXPR",
                    help="optimal: an inequality every added run satisfies (repeatable)")
    ag.add_argument("--starts", type=whole_number(1, 1000), default=None, metavar="N", help=argparse.SUPPRESS)
    _base(ag, factors=False)
    ds = sub.add_parser("definitive-screening", help="definitive screening design (Jones & Nachtsheim 2011)",
                        description="Three-level definitive screening design from an exact conference matrix.")
    _base(ds)
    ds.add_argument("--center", type=whole_number(0), default=None, metavar="N",
                    help="centre runs (default 1; 2 with two-level categoric factors, one at each level)")
    fr = sub.add_parser("fractional-factorial", help="two-level fractional factorial (by resolution or generators)",
                        description="Two-level fractional factorial; the alias structure is printed.")
    _base(fr)
    g = fr.add_mutually_exclusive_group(required=True)
    g.add_argument("--resolution", type=whole_number(3), metavar="R", help="resolution (3, 4, 5, ...)")
    g.add_argument("--generator", metavar="WORDS", help="generators in factor letters, e.g. 'A B C ABC'")
    fr.add_argument("--center", type=whole_number(0), default=0, metavar="N", help="centre runs (default 0)")
    pb = sub.add_parser("plackett-burman", help="Plackett-Burman screening design",
                        description="Plackett-Burman two-level screening design (runs a multiple of 4).")
    _base(pb)
    pb.add_argument("--center", type=whole_number(0), default=0, metavar="N", help="centre runs (default 0)")
    for name, hlp in (("latin-hypercube", "Latin hypercube (space-filling, for virtual runs)"),
                      ("sobol", "scrambled Sobol' points (space-filling, for virtual runs)")):
        sp = sub.add_parser(name, help=hlp, description=hlp + "; on a box or a constrained region.")
        _base(sp, constraint=True)
        sp.add_argument("--runs", type=whole_number(2), required=True, metavar="N", help="number of runs")
        if name == "latin-hypercube":
            sp.add_argument("--criterion", default="discrepancy", choices=["discrepancy", "maximin"],
                            help="space-filling criterion (default discrepancy)")
    bb = sub.add_parser("box-behnken", help="Box-Behnken design, 3-7, 9-12 or 16 factors (Box & Behnken 1960)",
                        description="Box-Behnken design for 3 to 7, 9 to 12 or 16 factors as published by Box "
                                    "& Behnken (1960).")
    _common(bb, "3", "centre runs (per block when blocked; default 3)")
    bb.add_argument("--blocks", type=whole_number(1), default=None, metavar="N",
                    help="orthogonal blocks: 3 for 4 factors, 2 for 5, 5 for 9, 6 for 16 (default 1)")
    cc = sub.add_parser("central-composite", help="central composite design (2^k cube + star + centre)",
                        description="Central composite design with a full 2^k cube.")
    _common(cc, "4,4", "centre runs: N, or CUBE,STAR (default 4,4)")
    cc.add_argument("--alpha", default=None, metavar="RULE|X",
                    help="rotatable (default), orthogonal, practical, face, or a number")
    cc.add_argument("--face", default="circumscribed", choices=["circumscribed", "inscribed", "faced"],
                    help="where the star points sit (default circumscribed)")
    cc.add_argument("--blocks", type=whole_number(1), default=None, metavar="N",
                    help="2: cube and star in separate blocks (default 1)")
    ff = sub.add_parser("full-factorial", help="full factorial, equally spaced levels (default 2^k)",
                        description="Full factorial design with equally spaced levels (two by default, as "
                                    "Design-Expert and JMP: the classic factorial, augmented to a CCD with "
                                    "design augment --method ccd).")
    _common(ff, "0", "extra centre runs (default 0)")
    ff.add_argument("--levels", type=whole_number(2), default=2, metavar="N", help="levels per factor (default 2)")
    _mixture_parsers(sub)


def _split_plot_parser(sub: Any) -> None:
    """``split-plot`` (issue 23): hard-to-change factors held constant within whole plots."""
    from .options import number

    sp = sub.add_parser("split-plot", help="optimal split-plot design (hard-to-change factors in whole plots)",
                        description="Optimal split-plot design (Goos & Vandebroek 2003, 2004): the hard-to-change "
                                    "factors take one setting per whole plot, the others one per run; coordinate "
                                    "exchange on the GLS information X'V^-1 X with V = I + eta J per whole plot "
                                    "(eta = sigma^2 whole plot / sigma^2). The CSV adds a whole_plot column; the "
                                    "whole plots run in random order and the runs in random order within each.")
    _base(sp, constraint=True)
    sp.add_argument("--hard-to-change", action="append", required=True, metavar="NAME",
                    help="a factor (name) held constant within each whole plot (repeatable)")
    sp.add_argument("--whole-plots", type=whole_number(1), required=True, metavar="W",
                    help="number of whole plots (at least the whole-plot model terms + 1)")
    sp.add_argument("--runs", type=whole_number(1), required=True, metavar="N",
                    help="total runs; N/W per whole plot (when W does not divide N, the first N mod W whole "
                         "plots hold one run more, and the summary says so)")
    sp.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                    help="the model the design supports (default quadratic)")
    sp.add_argument("--criterion", default="D", type=str.upper, choices=["D", "I"],
                    help="optimality criterion on the GLS information (default D)")
    sp.add_argument("--variance-ratio", type=number(0, 1e6), default=1.0, metavar="ETA",
                    help="eta = sigma^2 whole plot / sigma^2, 0 to 1e6 (default 1)")
    sp.add_argument("--starts", type=whole_number(1, 1000), default=None, metavar="N",
                    help="random starts of the exchange (default 20 for up to 21 model terms, else 6)")
    sp.add_argument("--very-hard-to-change", action="append", default=None, metavar="NAME",
                    help="split-split-plot: a factor (name) held constant within each whole plot (repeatable); "
                         "the --hard-to-change factors are then held within sub-plots nested in the whole plots "
                         "(needs --subplots; the CSV adds a subplot column)")
    sp.add_argument("--subplots", type=whole_number(1), default=None, metavar="S",
                    help="split-split-plot: the number of sub-plots in all (S/W per whole plot, N/S runs each)")
    sp.add_argument("--subplot-variance-ratio", type=number(0, 1e6), default=1.0, metavar="ETA",
                    help="split-split-plot: eta_s = sigma^2 sub-plot / sigma^2, 0 to 1e6 (default 1)")
    st = sub.add_parser("strip-plot", help="optimal strip-plot design (row factors per row strip, column factors "
                                           "per column strip)",
                        description="Optimal strip-plot design (Arnouts, Goos & Jones 2010): R row strips cross C "
                                    "column strips, one run per cell; the --row-factor factors take one setting per "
                                    "row strip (the first processing stage), the --column-factor ones one per column "
                                    "strip (the second), any other factor one per run. Coordinate exchange on the "
                                    "GLS information X'V^-1 X with V = I + eta_r Z_r Z_r' + eta_c Z_c Z_c'. The CSV "
                                    "adds the columns strip_row and strip_column (fit --random-effect strip_row "
                                    "--random-effect strip_column analyses it).")
    _base(st)
    st.add_argument("--row-factor", action="append", required=True, metavar="NAME",
                    help="a factor (name) set once per row strip (repeatable)")
    st.add_argument("--column-factor", action="append", required=True, metavar="NAME",
                    help="a factor (name) set once per column strip (repeatable)")
    st.add_argument("--rows", type=whole_number(1, 600), required=True, metavar="R", help="number of row strips")
    st.add_argument("--columns", type=whole_number(1, 600), required=True, metavar="C",
                    help="number of column strips (R x C runs, at most 600)")
    st.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                    help="the model the design supports (default quadratic)")
    st.add_argument("--criterion", default="D", type=str.upper, choices=["D", "I"],
                    help="optimality criterion on the GLS information (default D)")
    st.add_argument("--row-variance-ratio", type=number(0, 1e6), default=1.0, metavar="ETA",
                    help="eta_r = sigma^2 row strip / sigma^2, 0 to 1e6 (default 1)")
    st.add_argument("--column-variance-ratio", type=number(0, 1e6), default=1.0, metavar="ETA",
                    help="eta_c = sigma^2 column strip / sigma^2, 0 to 1e6 (default 1)")
    st.add_argument("--starts", type=whole_number(1, 1000), default=None, metavar="N",
                    help="random starts of the exchange (default 20 for up to 21 model terms, else 6)")


def _strip_plot(args: argparse.Namespace) -> Any:
    """Build the strip-plot design; bad input is an InputError naming the option."""
    from ..design.multi_stratum import strip_plot

    space = _space(args)
    with about_options(options=_DESIGN_OPTIONS, default="--factor"):
        return strip_plot(space, args.row_factor, args.column_factor, args.rows, args.columns, model=args.model,
                          criterion=args.criterion,
                          variance_ratios={"strip_row": args.row_variance_ratio,
                                           "strip_column": args.column_variance_ratio},
                          seed=args.seed, starts=args.starts, randomize=not args.no_randomize)


def _split_split_plot(args: argparse.Namespace) -> Any:
    """Build the split-split-plot design (``--very-hard-to-change``); bad input is an
    InputError naming the option."""
    from ..design.multi_stratum import split_split_plot
    from ..io import InputError

    if args.subplots is None:
        raise InputError("--subplots: a split-split-plot design (--very-hard-to-change) needs the number of "
                         "sub-plots")
    if args.constraint:
        raise InputError("--constraint: not available for a split-split-plot design (--very-hard-to-change)")
    space = _space(args)
    with about_options(options=_DESIGN_OPTIONS, default="--factor"):
        return split_split_plot(space, args.very_hard_to_change, args.hard_to_change, args.whole_plots,
                                args.subplots, args.runs, model=args.model, criterion=args.criterion,
                                variance_ratios={"whole_plot": args.variance_ratio,
                                                 "subplot": args.subplot_variance_ratio},
                                seed=args.seed, starts=args.starts, randomize=not args.no_randomize)


def _split_plot_ccd_parser(sub: Any) -> None:
    """``split-plot-ccd``: the equivalent-estimation split-plot central composite design."""
    from .options import number

    sc = sub.add_parser("split-plot-ccd", help="split-plot central composite design (OLS = GLS estimates)",
                        description="Equivalent-estimation split-plot central composite design (after Vining, "
                                    "Kowalski & Montgomery 2005): whole plots at the whole-plot cube points hold the "
                                    "sub-plot cube, those at the whole-plot star points hold sub-plot centre runs, "
                                    "the centre whole plot(s) hold the sub-plot star points; equal whole plots and "
                                    "matched star distances make the OLS and GLS (REML) estimates of the quadratic "
                                    "model coincide for every variance ratio. The CSV adds a whole_plot column.")
    _base(sc)
    sc.add_argument("--hard-to-change", action="append", required=True, metavar="NAME",
                    help="a factor (name) held constant within each whole plot (repeatable; 1 to 5)")
    sc.add_argument("--alpha", type=number(0, MAX_ALPHA, above=True), default=None, metavar="A",
                    help="whole-plot star distance in coded units, above sqrt(whole-plot factors); the sub-plot one "
                         "follows (default: one common distance sqrt(k_wp + 2^(k_sp-1)))")
    sc.add_argument("--center-whole-plots", type=whole_number(1, 100), default=1, metavar="K",
                    help="whole plots at the whole-plot centre, each with the sub-plot star and centre runs "
                         "(default 1)")


def _split_plot_ccd(args: argparse.Namespace) -> Any:
    """Build the split-plot CCD; bad input is an InputError naming the option."""
    from ..design.split_plot import split_plot_ccd

    space = _space(args)
    with about_options(options=_DESIGN_OPTIONS, default="--factor"):
        return split_plot_ccd(space, args.hard_to_change, alpha=args.alpha,
                              center_whole_plots=args.center_whole_plots, seed=args.seed,
                              randomize=not args.no_randomize)


def _split_plot(args: argparse.Namespace) -> Any:
    """Build the split-plot design from the parsed arguments; bad input is an InputError
    naming the option."""
    from ..design.split_plot import split_plot
    from ..io import InputError

    if args.very_hard_to_change:
        return _split_split_plot(args)
    if args.subplots is not None:
        raise InputError("--subplots: sub-plots belong to a split-split-plot design; name its whole-plot factors "
                         "with --very-hard-to-change")
    space = _space(args)
    cons = _constraints(args, space)
    with about_options(options=_DESIGN_OPTIONS, default="--factor"):
        return split_plot(space, args.hard_to_change, args.whole_plots, args.runs, model=args.model,
                          criterion=args.criterion, variance_ratio=args.variance_ratio, constraints=cons,
                          seed=args.seed, starts=args.starts, randomize=not args.no_randomize)


def _mixture_parsers(sub) -> None:
    """``simplex-lattice``, ``simplex-centroid`` and ``extreme-vertices`` (issue 22)."""
    note = (" The CSV holds one column per component with the real proportion (every run sums to "
            "--total) and the L-pseudo components as the coded columns coded_A, coded_B, ...")
    sl = sub.add_parser("simplex-lattice", help="{q, m} simplex-lattice mixture design",
                        description="Simplex-lattice mixture design: every blend whose proportions are "
                                    "0, 1/m, ..., 1 of the total." + note)
    sl.add_argument("--degree", type=whole_number(1, 100), required=True, metavar="M",
                    help="lattice degree m (proportions in steps of total/m)")
    sc = sub.add_parser("simplex-centroid", help="simplex-centroid mixture design (2^q - 1 blends)",
                        description="Simplex-centroid mixture design: the centroids of every face of the "
                                    "simplex (pure blends, 50:50 blends, ..., the overall centroid)." + note)
    ev = sub.add_parser("extreme-vertices", help="extreme vertices of a constrained mixture region",
                        description="Extreme-vertices mixture design (McLean & Anderson 1966): the vertices of "
                                    "the region cut from the simplex by the component bounds and linear "
                                    "constraints, optionally with edge, constraint-plane and overall "
                                    "centroids." + note)
    for p in (sl, sc):
        p.add_argument("--component", action="append", required=True, metavar="NAME",
                       help="a mixture component (repeat for each, in order; at least 2)")
        p.add_argument("--center", action="store_true", help="add one run at the overall centroid")
        p.add_argument("--axial", action="store_true",
                       help="add the q axial check blends ((q+1)/2q, 1/2q, ..., 1/2q of the total)")
    ev.add_argument("--component", action="append", required=True, metavar="NAME=LOW:HIGH",
                    help="a component and its bounds in real proportions (bare NAME: 0 to the total); "
                         "repeat for each, in order")
    ev.add_argument("--constraint", action="append", default=[], metavar="EXPR",
                    help="a linear inequality in the proportions, e.g. 'A + B <= 0.7' (repeatable)")
    ev.add_argument("--centroids", action="store_true",
                    help="add edge centroids, constraint-plane centroids and the overall centroid")
    for p in (sl, sc, ev):
        p.add_argument("--total", default="1", metavar="T", help="the total the proportions sum to (default 1)")
        p.add_argument("--factor", action="append", default=None, metavar="NAME=LOW:HIGH",
                       help="a process factor (repeatable): the crossed mixture-process design, every blend at "
                            "every point of the two-level full factorial in the process factors")
        _order_and_output(p)


#: Most runs any design kind writes (a full factorial's limit): --replicates and --lof-points past it
#: are refused by name before any work (10**19 replicates once blamed --runs).
MAX_DESIGN_RUNS = 100_000

#: Most centre runs per block: replicates of one point, far beyond any experiment.
MAX_CENTER = 1000


def _center(text: str, pair: bool):
    from ..io import InputError, quote_user_value

    parts = [t.strip() for t in str(text).split(",")]
    want = f"a whole number{' or CUBE,STAR' if pair else ''}"
    try:
        vals = [int(t) for t in parts]
    except ValueError:
        raise InputError(f"--center: expected {want}, got {quote_user_value(text)}") from None
    if any(v < 0 for v in vals):
        raise InputError(f"--center: the number of centre points must not be negative (got {quote_user_value(text)})")
    if any(v > MAX_CENTER for v in vals):
        raise InputError(f"--center: at most {MAX_CENTER} centre points (got {quote_user_value(text)})")
    if len(vals) == 1:
        return vals[0]
    if pair and len(vals) == 2:
        return tuple(vals)
    raise InputError(f"--center: expected {want}, got {quote_user_value(text)}")


def run(args) -> int:
    import math
    from pathlib import Path

    from ..design import as_factor_space, box_behnken, central_composite, full_factorial
    from ..io import InputError, check_output, quote_user_value

    out = Path(args.output)
    check_output(out, force=args.force, option="-o/--output")
    if args.kind == "augment":
        return _augment(args, out)
    if args.kind in _MIXTURE_KINDS or (args.kind == "optimal" and args.component):
        design = _mixture(args)
        write_design(design, out, args)
        print(design.summary())
        print(f"wrote {out}")
        return 0
    if args.kind in _NEW_KINDS or args.kind in ("split-plot", "split-plot-ccd", "strip-plot"):
        design = (_split_plot(args) if args.kind == "split-plot" else _split_plot_ccd(args)
                  if args.kind == "split-plot-ccd" else _strip_plot(args) if args.kind == "strip-plot"
                  else _new_kind(args))
        write_design(design, out, args)
        print(design.summary())
        print(f"wrote {out}")
        return 0
    space = as_factor_space(args.factor)
    randomize = not args.no_randomize
    if args.kind == "box-behnken":
        design = box_behnken(space, center=_center(args.center, False), blocks=args.blocks,
                             seed=args.seed, randomize=randomize)
    elif args.kind == "central-composite":
        alpha = args.alpha
        if alpha is not None:
            try:
                alpha = float(alpha)
            except ValueError:
                pass
            else:
                if not (math.isfinite(alpha) and 0 < alpha <= MAX_ALPHA):
                    raise InputError(f"--alpha: expected rotatable, orthogonal, practical, face or a number "
                                     f"> 0 and at most {MAX_ALPHA:g}, got {quote_user_value(args.alpha)}")
        design = central_composite(space, alpha=alpha, face=args.face, center=_center(args.center, True),
                                   blocks=args.blocks, seed=args.seed, randomize=randomize)
    else:
        design = full_factorial(space, levels=args.levels, center=_center(args.center, False),
                                seed=args.seed, randomize=randomize)
    write_design(design, out, args)
    print(design.summary())
    print(f"wrote {out}")
    return 0


#: The largest star distance ``--alpha`` [coded units] a design command takes: a star point a
#: thousand half-ranges from the centre is no experiment, and beyond it coded and actual
#: values could overflow (issue 26).
MAX_ALPHA = 1000.0

#: The option of a design function's parameter that an error names (by its ``parameter``,
#: :class:`rsm_lrg.errors.ParameterError`) where it is not ``--`` and the parameter's name
#: (``hard_to_change`` -> ``--hard-to-change``) nor in :data:`.errors.PARAMETER_OPTIONS`.
_DESIGN_OPTIONS = {
    "factors": "--factor", "process": "--factor", "components": "--component", "bounds": "--component",
    "generators": "--generator", "very_hard_to_change": "--very-hard-to-change", "row_factors": "--row-factor",
    "column_factors": "--column-factor", "subplots": "--subplots", "rows": "--rows", "columns": "--columns",
}

#: Kinds handled by :func:`_new_kind` (added with issue 13).
_NEW_KINDS = ("optimal", "definitive-screening", "fractional-factorial", "plackett-burman", "latin-hypercube",
              "sobol")


#: Mixture kinds handled by :func:`_mixture` (issue 22).
_MIXTURE_KINDS = ("simplex-lattice", "simplex-centroid", "extreme-vertices")


def _component_bounds(specs: list[str], total: float) -> dict[str, tuple[float, float]]:
    """``--component NAME=LOW:HIGH`` (or bare ``NAME``: 0 to the total) as ``{name: (low, high)}``."""
    import math

    from ..io import InputError, quote_user_value

    out: dict[str, tuple[float, float]] = {}
    for spec in specs:
        name, eq, rng = spec.partition("=")
        name = name.strip()
        if not name:
            raise InputError(f"--component: an empty name in {quote_user_value(spec)}")
        if name in out:
            raise InputError(f"--component: {quote_user_value(name)} is given twice")
        if not eq:
            out[name] = (0.0, total)
            continue
        lo, colon, hi = rng.partition(":")
        try:
            low, high = float(lo), float(hi)
        except ValueError:
            low = high = math.nan
        if not colon or not (math.isfinite(low) and math.isfinite(high)):
            raise InputError(f"--component: expected NAME=LOW:HIGH with finite numbers, got {quote_user_value(spec)}")
        out[name] = (low, high)
    return out


def _mixture(args):
    """Build a mixture design from the parsed arguments; bad input is an InputError."""
    import math

    from ..design.mixture import cross_process, extreme_vertices, simplex_centroid, simplex_lattice
    from ..io import InputError, quote_user_value

    try:
        total = float(args.total)
    except ValueError:
        total = math.nan
    if not (math.isfinite(total) and 0 < total <= 1e15):
        raise InputError(f"--total: expected a finite number > 0 and at most 1e15, got {quote_user_value(args.total)}")
    process = getattr(args, "factor", None)
    if process:
        _space(args)  # a bad process factor is named (--factor) before the design is built
    randomize = not args.no_randomize and not process  # a crossed design is randomised once crossed
    with about_options(options=_DESIGN_OPTIONS, default="--component", catch=(TypeError, ValueError)):
        if args.kind == "optimal":
            from ..design.mixture_optimal import mixture_optimal

            sizes = _block_sizes(args.block_size)
            if sizes is not None and args.blocks is None:
                raise InputError("--block-size: give the number of blocks too (--blocks N)")
            criterion = args.criterion or ("D" if args.blocks is not None else "I")
            return mixture_optimal(_component_bounds(args.component, total), model=args.model or "mixture-quadratic",
                                   criterion=criterion, runs=args.runs, lof_points=args.lof_points,
                                   replicates=args.replicates, constraints=args.constraint or None, total=total,
                                   process=process, seed=args.seed, starts=args.starts,
                                   randomize=not args.no_randomize, blocks=args.blocks, block_size=sizes)
        if args.kind == "extreme-vertices":
            bounds = _component_bounds(args.component, total)
            design = extreme_vertices(bounds, constraints=args.constraint or None, centroids=args.centroids,
                                      total=total, seed=args.seed, randomize=randomize)
        elif args.kind == "simplex-lattice":
            design = simplex_lattice([c.strip() for c in args.component], args.degree, center=args.center,
                                     axial=args.axial, total=total, seed=args.seed, randomize=randomize)
        else:
            design = simplex_centroid([c.strip() for c in args.component], center=args.center, axial=args.axial,
                                      total=total, seed=args.seed, randomize=randomize)
        if process:
            design = cross_process(design, process, seed=args.seed, randomize=not args.no_randomize)
        return design


def _block_sizes(text: str | None) -> int | list[int] | None:
    """``--block-size N`` or ``N1,N2,...`` as a number or a list (whole numbers >= 1)."""
    from ..io import InputError, quote_user_value

    if text is None:
        return None
    parts = [t.strip() for t in str(text).split(",")]
    try:
        vals = [int(t) for t in parts]
    except ValueError:
        vals = []
    if not vals or any(v < 1 or v > MAX_DESIGN_RUNS for v in vals):
        raise InputError(f"--block-size: expected a whole number of runs (1 to {MAX_DESIGN_RUNS}) or one per block "
                         f"separated by commas, got {quote_user_value(text)}")
    return vals[0] if len(vals) == 1 else vals


def _space(args):
    from ..design import as_factor_space
    from ..io import InputError

    try:
        return as_factor_space(args.factor)
    except ValueError as exc:
        raise InputError(f"--factor: {exc}") from None


def _constraints(args, space):
    from ..design.constraints import Constraints
    from ..io import InputError

    try:
        return Constraints.parse(list(getattr(args, "constraint", []) or []), space)
    except ValueError as exc:
        raise InputError(f"--constraint: {exc}") from None


def _new_kind(args):
    from ..io import InputError

    if args.kind == "optimal":
        if not args.factor:
            raise InputError("--factor: the optimal design needs its factors (--factor NAME=LOW:HIGH, repeatable) "
                             "or mixture components (--component)")
        if args.blocks is not None or args.block_size is not None:
            raise InputError(f"--{'blocks' if args.blocks is not None else 'block-size'}: blocks in an optimal design "
                             "are available for mixtures (--component); for factors use a blocked central composite "
                             "or Box-Behnken design")
        if args.criterion is None:
            args.criterion = "I"
        if args.model is None:
            args.model = "quadratic"
        if args.model not in ("linear", "2fi", "quadratic", "cubic"):
            raise InputError(f"--model: {args.model} is a mixture model; give the components with --component")
    space = _space(args)
    randomize = not args.no_randomize
    if args.kind == "optimal":
        from ..design.optimal import optimal

        cons = _constraints(args, space)
        try:
            return optimal(space, model=args.model, criterion=args.criterion, runs=args.runs,
                           lof_points=args.lof_points, replicates=args.replicates, constraints=cons,
                           seed=args.seed, starts=args.starts, randomize=randomize)
        except ValueError as exc:
            raise option_error(exc, options=_DESIGN_OPTIONS, default="--factor") from None
    with about_options(options=_DESIGN_OPTIONS, default="--factor"):
        if args.kind == "definitive-screening":
            from ..design.screening import definitive_screening

            return definitive_screening(space, center=args.center, seed=args.seed, randomize=randomize)
        if args.kind == "fractional-factorial":
            from ..design.screening import fractional_factorial

            try:
                return fractional_factorial(space, resolution=args.resolution, generators=args.generator,
                                            center=args.center, seed=args.seed, randomize=randomize)
            except ValueError as exc:
                raise option_error(exc, options=_DESIGN_OPTIONS,
                                   default="--generator" if args.generator is not None else "--resolution") from None
        if args.kind == "plackett-burman":
            from ..design.screening import plackett_burman

            return plackett_burman(space, center=args.center, seed=args.seed, randomize=randomize)
        from ..design.spacefill import latin_hypercube, sobol

        cons = _constraints(args, space)
        if args.kind == "latin-hypercube":
            return latin_hypercube(space, args.runs, criterion=args.criterion, constraints=cons, seed=args.seed,
                                   randomize=randomize)
        return sobol(space, args.runs, constraints=cons, seed=args.seed, randomize=randomize)


def _augment(args, out) -> int:
    """Read DESIGN.csv, add runs, write the original rows untouched and the new ones after."""
    import math
    from pathlib import Path

    import pandas as pd

    from ..design import Design
    from ..design.augment import augment
    from ..design.core import BLOCK_COLUMN
    from ..io import InputError, quote_user_value
    from .paths import read_input

    src = Path(args.design)
    if src.exists() and out.exists() and src.resolve() == out.resolve():
        raise InputError(f"-o/--output: {out} is the input design; an input file is never overwritten")
    df = read_input(args, src)
    try:
        design = Design.from_frame(df)
    except ValueError as exc:
        raise InputError(f"{src}: {exc}") from None
    if design.whole_plots is not None:  # added runs would need whole plots: nothing is guessed
        raise InputError(f"{src}: a split-plot design (column whole_plot) is not augmented here: the added runs "
                         "would need whole plots; make a new design with design split-plot")
    alpha = args.alpha
    try:
        alpha = float(alpha)
    except ValueError:
        pass
    else:
        if not (math.isfinite(alpha) and 0 < alpha <= MAX_ALPHA):
            raise InputError(f"--alpha: expected a rule or a number > 0 and at most {MAX_ALPHA:g}, "
                             f"got {quote_user_value(args.alpha)}")
    cons = None
    if args.constraint:
        cons = _constraints(args, design.factors)
    with about_options(options=_DESIGN_OPTIONS, default="--method"):
        aug = augment(design, args.method, model=args.model, criterion=args.criterion, runs=args.runs,
                      alpha=alpha, center=args.center, fold=args.fold, new_block=args.new_block,
                      constraints=cons, seed=args.seed, starts=args.starts, randomize=not args.no_randomize)
    new = aug.to_frame()
    new = new[new["std_order"] > design.n_runs]
    old = df.copy()
    if BLOCK_COLUMN in new.columns and BLOCK_COLUMN not in old.columns:
        pos = list(old.columns).index("run_order") + 1 if "run_order" in old.columns else 0
        old.insert(pos, BLOCK_COLUMN, 1)
    # the added rows in the columns of the input (responses and other columns left empty)
    names = {f.name for f in design.factors}
    add = pd.DataFrame({c: (new[c].to_numpy() if c in new.columns else [None] * len(new)) for c in old.columns})
    missing = [c for c in new.columns if c not in old.columns and c not in names]
    if missing:
        raise InputError(f"{src}: lacks the column(s) {', '.join(missing)} of a design CSV")
    merged = pd.concat([old, add.astype(object)], ignore_index=True) if len(old) else add
    write_design_frame(merged, out, args)
    print(aug.summary())
    print(f"wrote {out}")
    return 0
