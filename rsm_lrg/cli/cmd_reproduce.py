"""``rsm-lrg reproduce``: the whole paper from the embedded data, paper vs toolkit side by side."""

from __future__ import annotations

import argparse

from .options import add_force, add_json

NAME = "reproduce"
HELP = "reproduce the paper from the embedded data; print paper vs toolkit and write an HTML page"
DESCRIPTION = (
    "Run Su, Zhang & Yang (2023) end to end from the embedded data: the physics (Eqs. 1-18), "
    "the thermal transient (Fig. 5), the stage comparison (Fig. 9), the response surface "
    "(Eq. 19, Table 5), the optimum and the confirmation run. Prints quantity, paper value, "
    "toolkit value, relative difference, tolerance and verdict, and writes "
    "DIR/paper-reproduction.html. Exit status 0 when no row FAILs (outside its tolerance with no "
    "known reason), 1 when one does; a 'not yet' row (outside its tolerance, or not computable, "
    "for the documented reason the row states) does not change the exit status, and the "
    "verdict line counts those rows."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-o", "--output", metavar="DIR", default="reports",
                        help="directory for paper-reproduction.html (default: reports/; created if missing)")
    parser.add_argument("--no-html", action="store_true", help="print the table only")
    add_json(parser)
    add_force(parser)


def outputs(args: argparse.Namespace) -> list[tuple[str, str]]:
    """The files this run will write, for the checks made before it starts: DIR (made when
    missing, so its nearest existing parent must be a writable directory), the page in it and
    the --json file."""
    import os
    from pathlib import Path

    from ..io import InputError

    out = []
    if not args.no_html:
        d = Path(args.output)
        if not str(args.output).strip():
            raise InputError("cannot write -o/--output '': an empty path was given")
        if d.is_dir():
            out.append(("-o/--output", str(d / "paper-reproduction.html")))
        elif os.path.lexists(d):
            raise InputError(f"cannot write -o/--output {args.output}: it is not a directory")
        else:
            up = d.absolute().parent
            while not up.exists():
                up = up.parent
            if not up.is_dir() or not os.access(up, os.W_OK | os.X_OK):
                raise InputError(f"cannot write -o/--output {args.output}: cannot create the directory in {up}")
    if args.json is not None:
        out.append(("--json", args.json))
    return out


def run(args: argparse.Namespace) -> int:
    import sys
    from pathlib import Path

    from ..io import InputError, dump_json
    from ..paper import reproduce, write_reproduction

    out = Path(args.output) / "paper-reproduction.html"
    if not args.no_html:
        if Path(args.output).exists() and not Path(args.output).is_dir():
            raise InputError(f"{args.output}: is not a directory")
        if out.exists() and not args.force:  # before the long run
            raise InputError(f"{out}: already exists; use --force to overwrite it")

    def progress(msg: str) -> None:
        print(f"reproduce: {msg}", file=sys.stderr, flush=True)

    rep = reproduce(progress=progress)
    if args.json and args.json != "-":
        dump_json(rep.to_dict(), args.json, force=args.force)
    if args.json == "-":
        dump_json(rep.to_dict(), "-")
    else:
        sys.stdout.write(rep.to_text())
    if not args.no_html:
        progress("writing the HTML page (figures)")
        made = not Path(args.output).exists()
        try:
            path = write_reproduction(rep, args.output, force=args.force)
        except BaseException:  # an error or a signal: a directory made for the page goes with it
            if made and Path(args.output).is_dir() and not any(Path(args.output).iterdir()):
                Path(args.output).rmdir()
            raise
        print(f"wrote {path}", file=sys.stderr if args.json == "-" else sys.stdout)
    return 0 if rep.ok else 1
