"""``rsm-lrg design``: write a design CSV (Box-Behnken, central composite, full factorial)."""

from __future__ import annotations

import argparse

from ._common import add_force, whole_number

NAME = "design"
HELP = "write a design CSV (box-behnken, central-composite, full-factorial)"
DESCRIPTION = (
    "Generate an experimental design and write it as CSV: std_order, run_order, block (when "
    "blocked), the coded columns coded_A, coded_B, ... and the actual columns named after the "
    "factors. The run order is randomised from --seed (within blocks) unless --no-randomize."
)


def _common(p: argparse.ArgumentParser, center_default, center_help: str) -> None:
    p.add_argument("--factor", action="append", required=True, metavar="NAME=LOW:HIGH",
                   help="a factor and the levels coded -1 and +1 (repeat for each factor, in order)")
    p.add_argument("--center", default=center_default, metavar="N", help=center_help)
    p.add_argument("--seed", type=whole_number(0), default=None, metavar="N",
                   help="seed of the randomised run order (default: drawn and printed)")
    p.add_argument("--no-randomize", action="store_true", help="run order = standard order")
    p.add_argument("-o", "--output", required=True, metavar="PATH", help="the design CSV to write")
    add_force(p)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="kind", metavar="KIND", required=True)
    bb = sub.add_parser("box-behnken", help="Box-Behnken design, 3 to 7 factors (Box & Behnken 1960)",
                        description="Box-Behnken design for 3 to 7 factors as published by Box & Behnken (1960).")
    _common(bb, "3", "centre runs (per block when blocked; default 3)")
    bb.add_argument("--blocks", type=whole_number(1), default=None, metavar="N",
                    help="orthogonal blocks: 3 for 4 factors, 2 for 5 factors (default 1)")
    cc = sub.add_parser("central-composite", help="central composite design (2^k cube + star + centre)",
                        description="Central composite design with a full 2^k cube.")
    _common(cc, "4,4", "centre runs: N, or CUBE,STAR (default 4,4)")
    cc.add_argument("--alpha", default=None, metavar="RULE|X",
                    help="rotatable (default), orthogonal, practical, face, or a number")
    cc.add_argument("--face", default="circumscribed", choices=["circumscribed", "inscribed", "faced"],
                    help="where the star points sit (default circumscribed)")
    cc.add_argument("--blocks", type=whole_number(1), default=None, metavar="N",
                    help="2: cube and star in separate blocks (default 1)")
    ff = sub.add_parser("full-factorial", help="full factorial, equally spaced levels (default 3^k)",
                        description="Full factorial design with equally spaced levels.")
    _common(ff, "0", "extra centre runs (default 0)")
    ff.add_argument("--levels", type=whole_number(2), default=3, metavar="N", help="levels per factor (default 3)")


#: Most centre runs per block: replicates of one point, far beyond any experiment.
MAX_CENTER = 1000


def _center(text: str, pair: bool):
    from ..io import quote_user_value

    parts = [t.strip() for t in str(text).split(",")]
    want = f"a whole number{' or CUBE,STAR' if pair else ''}"
    try:
        vals = [int(t) for t in parts]
    except ValueError:
        raise ValueError(f"--center: expected {want}, got {quote_user_value(text)}") from None
    if any(v < 0 for v in vals):
        raise ValueError(f"--center: the number of centre points must not be negative (got {quote_user_value(text)})")
    if any(v > MAX_CENTER for v in vals):
        raise ValueError(f"--center: at most {MAX_CENTER} centre points (got {quote_user_value(text)})")
    if len(vals) == 1:
        return vals[0]
    if pair and len(vals) == 2:
        return tuple(vals)
    raise ValueError(f"--center: expected {want}, got {quote_user_value(text)}")


def run(args) -> int:
    import math
    from pathlib import Path

    from ..design import as_factor_space, box_behnken, central_composite, full_factorial
    from ..io import InputError, quote_user_value

    out = Path(args.output)
    if out.exists() and not args.force:
        raise InputError(f"{out}: already exists; use --force to overwrite it")
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
                if not (math.isfinite(alpha) and alpha > 0):
                    raise InputError(f"--alpha: expected rotatable, orthogonal, practical, face or a finite "
                                     f"number > 0, got {quote_user_value(args.alpha)}")
        design = central_composite(space, alpha=alpha, face=args.face, center=_center(args.center, True),
                                   blocks=args.blocks, seed=args.seed, randomize=randomize)
    else:
        design = full_factorial(space, levels=args.levels, center=_center(args.center, False),
                                seed=args.seed, randomize=randomize)
    design.to_csv(out, force=args.force)
    print(design.summary())
    print(f"wrote {out}")
    return 0
