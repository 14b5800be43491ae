"""``rsm-lrg fit``: fit a response-surface model, print the ANOVA (Table 5 layout) and equation."""

from __future__ import annotations

import argparse

from ._common import about_file, add_force, add_json, add_model_inputs, print_notes

NAME = "fit"
HELP = "fit a response-surface model; print the ANOVA, statistics and equation"
DESCRIPTION = (
    "Fit a linear, 2FI or quadratic model by least squares in coded units and print the "
    "Design-Expert style ANOVA (partial sums of squares, lack of fit, pure error), the fit "
    "statistics, the coefficients, the equation in coded and actual terms and the canonical "
    "analysis. With --json - the JSON goes to standard output instead of the text."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_inputs(parser)
    parser.add_argument("--reduce", action="store_true",
                        help="backward elimination keeping hierarchy; the output carries only the kept terms")
    from ._common import number

    parser.add_argument("--alpha-out", type=number(0, 1, above=True, below=True), default=0.1, metavar="A",
                        help="with --reduce and --criterion p: remove terms while p > A (default 0.1)")
    parser.add_argument("--criterion", default="p", choices=["p", "aicc"],
                        help="with --reduce: remove by p-value (default) or while AICc falls")
    parser.add_argument("--transform", default=None, metavar="log|log10|sqrt|inverse|power=L",
                        help="fit a transformed response (predictions are back-transformed)")
    parser.add_argument("--transform-constant", type=number(), default=0.0, metavar="K",
                        help="add K to the response before transforming (default 0)")
    parser.add_argument("--diagnostics", action="store_true",
                        help="also print per-run diagnostics and the Box-Cox recommendation (JSON key 'diagnostics')")
    add_json(parser)
    parser.add_argument("--report", metavar="PATH", default=None, help="also write a self-contained HTML report")
    add_force(parser)


def _write_report(result, path, force: bool) -> None:
    import importlib

    try:
        mod = importlib.import_module("rsm_lrg.report")
    except ImportError:
        mod = None
    writer = getattr(mod, "write_report", None) if mod is not None else None
    if writer is None:
        raise ValueError(f"{path}: --report is not available yet in this version (no HTML report writer)")
    writer(result, path, force=force)


def run(args: argparse.Namespace) -> int:
    from ..io import dump_json, read_table
    from ..model import fit

    if args.transform is not None:  # a bad --transform is named before any data is read
        from ..io import InputError, quote_user_value
        from ..model.transform import parse_transform

        try:
            parse_transform(args.transform, args.transform_constant)
        except ValueError as exc:
            raise InputError(f"--transform {quote_user_value(args.transform)}: {exc}") from None
    data = read_table(args.data)
    extra = {}
    with about_file(args.data):
        tr = None
        if args.transform is not None:
            from ..model.data import response_values
            from ..model.transform import parse_transform

            tr = parse_transform(args.transform, args.transform_constant)
            if args.response not in data.columns:
                raise ValueError(f"response column {args.response!r} not found")
            y = response_values(data, args.response)[0]  # NaN where empty: that run is left out
            tr.check(y, args.response)
            data = data.copy()
            data[args.response] = tr.forward(y)
        terms = None
        if args.reduce:
            from ..model.reduce import reduce_terms

            red = reduce_terms(data, args.response, factors=args.factor, block=args.block, model=args.model,
                               alpha_out=args.alpha_out, criterion=args.criterion)
            terms = list(red.kept[1:])
            extra["reduction"] = red.to_dict()
        result = fit(data, args.response, factors=args.factor, block=args.block, model=args.model, terms=terms)
        if args.diagnostics:
            diag = result.diagnostics()
            extra["diagnostics"] = diag.to_dict()
    shown = result
    if tr is not None:
        from ..model.transform import TransformedFit

        shown = TransformedFit(fit=result, transform=tr, response=args.response)
    out = dict(shown.to_dict(), **extra)
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.report:
        _write_report(result, args.report, args.force)
    if args.json == "-":
        print_notes(result.input_notes)  # the text output carries them otherwise
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        if "reduction" in extra:
            r = extra["reduction"]
            print(f"Backward elimination ({'p > ' + format(args.alpha_out, 'g') if r['criterion'] == 'p' else 'AICc'}, "
                  f"hierarchy kept): removed {', '.join(r['removed']) or 'nothing'}")
        print(shown.summary(), end="")
        if args.diagnostics:
            print()
            print(diag.summary(), end="")
    return 0
