"""``rsm-lrg physics``: the paper's physics chain for the given parameters."""

from __future__ import annotations

import argparse

from .options import add_force, add_json

NAME = "physics"
HELP = "the paper's physics chain (load, heat, convection, hinges, thermal, wear) for given parameters"
DESCRIPTION = (
    "Runs Eqs. 1-18 of Su, Zhang & Yang (2023) for one parameter set: defaults from the shipped "
    "data/lrg_shs15v.toml (paper, THK SHS15V catalog, documented assumptions), then --params-file, "
    "then each --param NAME=VALUE. Prints a table; --json writes the INTERFACE.md document."
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="override one parameter (repeatable), e.g. --param mu_k=0.01")
    p.add_argument("--params-file", metavar="PATH.toml",
                   help="TOML file of overrides (name = value, or [name] value = ...)")
    p.add_argument("--list-params", action="store_true",
                   help="list the parameters with units, physical ranges and sources, then exit")
    p.add_argument("--no-thermal", action="store_true", help="skip the thermal model (its numbers become null)")
    add_json(p)
    add_force(p)


def run(args) -> int:
    import sys

    from ..io import dump_json
    from ..physics.chain import physics_chain
    from ..physics.params import PARAM_INFO, PHYSICAL_RANGES, LRGParams, load_params, parse_assignments
    from ..present import format_g

    if args.list_params:
        for name, value in LRGParams().to_dict().items():
            info = PARAM_INFO[name]
            shown = format_g(value, 15, trim=True) if isinstance(value, float) else str(value)
            rng = (f" in [{format_g(PHYSICAL_RANGES[name][0], 6, trim=True)}, "
                   f"{format_g(PHYSICAL_RANGES[name][1], 6, trim=True)}]") if name in PHYSICAL_RANGES else ""
            source = str(info["source"]).strip()
            if "assumption" in info:  # the rationale once, marked, whatever the source field says
                why = str(info["assumption"]).strip()
                source = (f"ASSUMPTION: {why}" if source.upper() == "ASSUMPTION"
                          else f"{source}  [ASSUMPTION: {why}]")
            print(f"{name} = {shown} [{info['unit']}]{rng}  {source}")
        return 0
    overrides = parse_assignments(args.param)
    params = load_params(args.params_file, **overrides)
    result = physics_chain(params, thermal=not args.no_thermal)
    if args.json == "-":
        dump_json(result.to_dict(), "-")
        print(result.to_text(), file=sys.stderr)
    else:
        print(result.to_text())
        if args.json:
            dump_json(result.to_dict(), args.json, force=args.force)
    return 0
