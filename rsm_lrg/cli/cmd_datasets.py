"""``rsm-lrg datasets``: list the shipped tables, or write one (so a pip user has ``table4.csv``)."""

from __future__ import annotations

import argparse

from .options import add_force

NAME = "datasets"
HELP = "list the shipped data (Table 4, Table 3, the mixture and split-plot examples) or write one"
DESCRIPTION = (
    "Without NAME: list the tables shipped inside the package (name, rows x columns, file, source). "
    "With NAME: print that table as CSV, or write it with -o PATH (a directory gets the file under "
    "its own name, e.g. -o data writes data/table4.csv). With -o DIR and no NAME: write every table "
    "into DIR (created when missing), so that the README's data/table4.csv exists after "
    "'rsm-lrg datasets -o data'."
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("name", nargs="?", default=None, metavar="NAME",
                   help="table4, table3, table5, equation19, mixture-etch or cake-split-plot (or the file name)")
    p.add_argument("-o", "--output", metavar="PATH", default=None,
                   help="write the table to PATH (a file, or a directory); without NAME, every table into the directory")
    add_force(p)


def _targets(args: argparse.Namespace) -> list[tuple[str, str]]:
    """``(file inside the package, path to write)`` for each table this run writes."""
    import os

    from ..datasets import DATASETS, dataset
    from ..io import InputError

    if args.output is None:
        return []
    if not str(args.output).strip():
        raise InputError("cannot write -o/--output '': an empty path was given")
    if args.name is None:
        if os.path.lexists(args.output) and not os.path.isdir(args.output):
            raise InputError(f"-o/--output {args.output}: without NAME, -o names a directory for every table; "
                             "it is a file (give NAME to write one table)")
        return [(d.file, os.path.join(args.output, d.file)) for d in DATASETS]
    try:
        d = dataset(args.name)
    except ValueError as exc:
        raise InputError(f"NAME: {exc}") from None
    path = os.path.join(args.output, d.file) if os.path.isdir(args.output) else args.output
    return [(d.file, path)]


def outputs(args: argparse.Namespace) -> list[tuple[str, str]]:
    """The files this run writes, for the checks made before it starts (a directory that
    does not exist yet is made by the run: then its nearest existing parent must be a
    writable directory)."""
    import os
    from pathlib import Path

    from ..io import InputError

    targets = _targets(args)
    if args.name is None and args.output is not None and not os.path.isdir(args.output):
        up = Path(args.output).absolute().parent
        while not up.exists():
            up = up.parent
        if not up.is_dir() or not os.access(up, os.W_OK | os.X_OK):
            raise InputError(f"cannot write -o/--output {args.output}: cannot create the directory in {up}")
        return []
    return [("-o/--output", path) for _, path in targets]


def run(args: argparse.Namespace) -> int:
    import os
    import sys

    from ..datasets import DATASETS, data_path, dataset
    from ..io import InputError, write_output

    if args.output is None:
        if args.name is None:
            rows = []
            for d in DATASETS:
                lines = data_path(d.file).read_text(encoding="utf-8").splitlines()
                shape = f"{len(lines) - 1} x {len(lines[0].split(','))}"
                rows.append((d.name, shape, d.file, d.title))
            widths = [max(len(r[i]) for r in rows) for i in range(3)]
            for r in rows:
                print("  ".join(c.ljust(w) for c, w in zip(r[:3], widths)) + "  " + r[3])
            print("\nrsm-lrg datasets NAME prints one as CSV; -o PATH writes it (-o DIR without NAME: all).")
            return 0
        try:
            d = dataset(args.name)
        except ValueError as exc:
            raise InputError(f"NAME: {exc}") from None
        sys.stdout.write(data_path(d.file).read_text(encoding="utf-8"))
        return 0
    targets = _targets(args)
    if args.name is None:
        try:
            os.makedirs(args.output, exist_ok=True)
        except OSError as exc:
            raise InputError(f"cannot write -o/--output {args.output}: cannot create the directory "
                             f"({exc.strerror or type(exc).__name__})") from None
    for file, path in targets:
        write_output(path, data_path(file).read_bytes(), force=args.force)
    for _, path in targets:
        print(f"wrote {path}")
    return 0
