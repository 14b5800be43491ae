"""Whole-process cost of ``rsm-lrg fit`` against R's ``rsm`` (issue 11, item 3; not a test).

Runs, alternately and ``--repeat`` times each (after one warm-up round that is not counted):

* ``python -m rsm_lrg fit data/table4.csv --response tcr_c_per_min``
* ``rsm-lrg fit data/table4.csv --response tcr_c_per_min`` (the console script)
* ``Rscript benchmarks/r/fit_table4.R data/table4.csv`` (``rsm()`` + ``summary()`` on the same
  file, coded on the Table 3 levels as the toolkit codes them)
* ``rsm-lrg --help`` and ``python -c pass`` (the interpreter alone, for reference)

and measures each child's wall time and CPU time (user + system, from
``resource.getrusage(RUSAGE_CHILDREN)`` deltas, so the whole process tree of the child is
counted). It prints the medians and the median ratios Python / R.

Targets (issue 37, item 6): CPU time of the fit at most 1.5x R's; ``rsm-lrg --help`` under
0.15 s wall.

``--in-process`` also times the fit without the process around it: ``rsm_lrg.fit`` +
``str(summary())`` on Table 4 repeated in this process (``time.process_time``, after warm-up
fits) against ``rsm()`` + ``print(summary())`` repeated inside one R process
(``benchmarks/r/fit_table4_loop.R``, ``system.time``), alternating, as the median of the
per-round ratios (target at most 1.25x).

The fit of a plain CSV file of numbers (Table 4 is one) loads no pandas: the file is read
into a ``rsm_lrg.table.ColumnTable`` (``readers.parse_plain_csv``) and fitted as it is, so
``import pandas`` (with pyarrow, a base dependency, about 0.5 s of CPU, more than R's whole
run) is not paid; ``--floor`` prints ``import numpy`` and ``import numpy, pandas`` beside it.
The fit loads no SciPy either (the core uses NumPy's LAPACK and its own t/F tails) and asks
for one BLAS thread for a small input file (OpenBLAS's threads cost ~0.2 s CPU at start-up),
so it can cost less CPU than the bare ``import numpy`` line, which keeps the default threads.

The children run as an installed package runs: with byte-code caches (``__pycache__``, which
``pip install`` writes), so ``PYTHONDONTWRITEBYTECODE`` is removed from their environment and
the warm-up round writes the caches. ``--no-bytecode`` keeps the variable (then every run
compiles the package's sources again, about 0.1-0.2 s more).

The console script is the one beside the interpreter (``<prefix>/bin/rsm-lrg``), not a
version manager's shim on ``PATH`` (pyenv's adds a bash start-up of its own).

    python benchmarks/bench_cli.py               # 15 rounds
    python benchmarks/bench_cli.py --repeat 30 --json out.json
    python benchmarks/bench_cli.py --floor       # also the bare imports of numpy, pandas, scipy
    python benchmarks/bench_cli.py --in-process  # also fit + summary() in one process, against R's
    python benchmarks/bench_cli.py --root /tmp/old-checkout   # `python -m rsm_lrg` of another commit
    python benchmarks/bench_cli.py --simulate    # simulate's start-up on a 1-row design instead
    python benchmarks/bench_cli.py --simulate --root /tmp/old-checkout   # ... against another commit's

``--simulate`` (issue 37, item 6: "``simulate``'s start-up a fraction of a second") times, alternately
and instead of the fit, ``python -m rsm_lrg simulate ROW.csv --seed 1 -o OUT.csv`` on a design of one
row (Table 4's first run: 0.3 mm, 40 mm, 0.4 m/s, 30 m/s²), with ``--root`` the same command from
that checkout (the previous implementation, in the same rounds), and the anchors ``python -c
"import numpy"``, ``python -c "import numpy, pandas"`` and numba's start-up alone (importing numba
and loading one cached kernel: what a design of more than one row pays; a one-row batch runs its
kernels uncompiled, ``rsm_lrg.physics.jit``). It
prints the medians, the ratio simulate / ``import numpy`` (median of per-round ratios) and, with
``--root``, new / old.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
DATA = "data/table4.csv"
FIT_ARGS = ["fit", DATA, "--response", "tcr_c_per_min"]


def commands(other_root: bool = False) -> dict[str, list[str]]:
    cmds = {
        "python -m rsm_lrg fit": [sys.executable, "-m", "rsm_lrg", *FIT_ARGS],
    }
    if other_root:  # another checkout (--root): `python -m` imports it from the working directory
        cmds["python -m rsm_lrg --help"] = [sys.executable, "-m", "rsm_lrg", "--help"]
        return cmds | {k: v for k, v in commands().items() if k in ("Rscript rsm fit", "python -c pass")}
    beside = Path(sys.executable).parent / "rsm-lrg"
    script = str(beside) if beside.exists() else shutil.which("rsm-lrg")
    if script:
        cmds["rsm-lrg fit"] = [script, *FIT_ARGS]
        cmds["rsm-lrg --help"] = [script, "--help"]
    cmds["python -m rsm_lrg --help"] = [sys.executable, "-m", "rsm_lrg", "--help"]
    rscript = shutil.which("Rscript")
    if rscript:
        cmds["Rscript rsm fit"] = [rscript, str(HERE / "r" / "fit_table4.R"), DATA]
    cmds["python -c pass"] = [sys.executable, "-c", "pass"]
    return cmds


#: ``--floor``: what the libraries alone cost, whatever rsm_lrg does (numpy is needed by every
#: fit, pandas by a fit of a file that is not plain numbers; scipy.special and scipy.linalg are
#: what other parts of the model layer use).
FLOOR = {
    "import numpy": "import numpy",
    "import numpy, pandas": "import numpy, pandas",
    "  + scipy.special": "import numpy, pandas, scipy.special",
    "  + scipy.special, linalg": "import numpy, pandas, scipy.special, scipy.linalg",
}


ENV = dict(os.environ)


def run_once(cmd: list[str], cwd: Path | None = None) -> tuple[float, float]:
    """(wall, cpu) seconds of one child process (its whole tree), run in ``cwd`` (default ROOT)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=cwd or ROOT, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed ({proc.returncode}): {proc.stderr.decode()[-500:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


#: ``--simulate``'s anchors: the interpreter with numpy (the floor of any command), with pandas too,
#: and what numba costs before a first simulated row (its import and one kernel from its disk cache).
SIMULATE_ANCHORS = {
    "python -c 'import numpy'": "import numpy",
    "python -c 'import numpy, pandas'": "import numpy, pandas",
    "numba + one cached kernel": "from rsm_lrg.physics import leafcore; leafcore.leaf_parts(1.0)",
}


def simulate_startup(rounds: int, old_root: Path | None) -> dict:
    """``--simulate``: CPU and wall seconds of ``simulate`` on a 1-row design (this checkout and,
    with ``old_root``, that one's) against the anchors, alternating, medians and ratios."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        design = Path(tmp) / "row.csv"
        head, first = (ROOT / DATA).read_text().splitlines()[:2]
        cols = head.split(",")
        keep = [cols.index(c) for c in ("thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2")]
        design.write_text(",".join(cols[i] for i in keep) + "\n"
                          + ",".join(first.split(",")[i] for i in keep) + "\n")
        sim = [sys.executable, "-m", "rsm_lrg", "simulate", str(design), "--seed", "1", "-o",
               str(Path(tmp) / "runs.csv"), "--force"]
        cmds: dict[str, tuple[list[str], Path]] = {"simulate, 1 row": (sim, ROOT)}
        if old_root is not None:
            cmds["simulate, 1 row (--root)"] = (sim, old_root)
        for name, code in SIMULATE_ANCHORS.items():
            cmds[name] = ([sys.executable, "-c", code], ROOT)
        for cmd, cwd in cmds.values():  # warm-up: page cache, .pyc files, numba's cache
            run_once(cmd, cwd)
        times: dict[str, dict[str, list[float]]] = {k: {"wall": [], "cpu": []} for k in cmds}
        for _ in range(rounds):
            for name, (cmd, cwd) in cmds.items():
                w, c = run_once(cmd, cwd)
                times[name]["wall"].append(w)
                times[name]["cpu"].append(c)
    med = {k: {m: statistics.median(v[m]) for m in ("wall", "cpu")} for k, v in times.items()}
    print(f"simulate start-up: {rounds} rounds, {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; "
          f"medians [s]" + (f"; --root {old_root}" if old_root else ""))
    print(f"{'command':34s} {'wall':>8s} {'cpu':>8s}")
    for k, v in med.items():
        print(f"{k:34s} {v['wall']:8.3f} {v['cpu']:8.3f}")
    out: dict = {"rounds": rounds, "median_s": med}
    anchor = "python -c 'import numpy'"
    for k in ("simulate, 1 row", "simulate, 1 row (--root)"):
        if k in times:
            ratio = statistics.median(a / b for a, b in zip(times[k]["cpu"], times[anchor]["cpu"]))
            out[f"ratio {k} / import numpy"] = ratio
            print(f"{k} / import numpy: CPU {ratio:.2f}x (median of per-round ratios)")
    if old_root is not None:
        ratio = statistics.median(a / b for a, b in zip(times["simulate, 1 row"]["cpu"],
                                                        times["simulate, 1 row (--root)"]["cpu"]))
        out["ratio new / old"] = ratio
        print(f"simulate, 1 row, this checkout / --root: CPU {ratio:.2f}x (median of per-round ratios)")
    return out


def in_process(rounds: int, fits: int = 50) -> dict:
    """Median CPU milliseconds per ``fit`` + ``str(summary())`` here and per ``rsm()`` +
    ``print(summary())`` in R (``fits`` of each per round, alternating), and the median of the
    per-round ratios."""
    import pandas as pd

    import rsm_lrg

    rscript = shutil.which("Rscript")
    if not rscript:
        print("in process: Rscript not found, skipped")
        return {}
    data = pd.read_csv(ROOT / DATA)

    def python_ms() -> float:
        t = time.process_time()
        for _ in range(fits):
            str(rsm_lrg.fit(data, "tcr_c_per_min").summary())
        return (time.process_time() - t) * 1000 / fits

    def r_ms() -> float:
        proc = subprocess.run([rscript, str(HERE / "r" / "fit_table4_loop.R"), DATA, str(fits)], cwd=ROOT, env=ENV,
                              capture_output=True, text=True, check=True)
        return float(proc.stdout.split()[-1])

    for _ in range(5):
        python_ms()
    py, r = [], []
    for _ in range(rounds):
        py.append(python_ms())
        r.append(r_ms())
    ratio = statistics.median(a / b for a, b in zip(py, r))
    print(f"in process, fit + summary(): {statistics.median(py):.1f} ms against R's {statistics.median(r):.1f} ms "
          f"(CPU), {ratio:.2f}x (median of per-round ratios; target <= 1.25x: "
          f"{'met' if ratio <= 1.25 else 'NOT met'})")
    return {"python_ms": statistics.median(py), "r_ms": statistics.median(r), "ratio": ratio}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15, help="rounds (each runs every command once)")
    ap.add_argument("--json", default=None, help="also write the figures to this file")
    ap.add_argument("--no-bytecode", action="store_true",
                    help="keep PYTHONDONTWRITEBYTECODE (every run compiles the sources again)")
    ap.add_argument("--root", default=None,
                    help="run `python -m rsm_lrg` from another checkout (e.g. an older commit, for before/after)")
    ap.add_argument("--in-process", action="store_true",
                    help="also time fit + summary() inside one process against R's rsm() + summary() in one R process")
    ap.add_argument("--floor", action="store_true",
                    help="also time bare imports of numpy, pandas and scipy (the floor under any fit)")
    ap.add_argument("--simulate", action="store_true",
                    help="instead, time simulate's start-up on a 1-row design against `import numpy` "
                         "(and, with --root, against that checkout's simulate)")
    args = ap.parse_args()
    if not args.no_bytecode:
        ENV.pop("PYTHONDONTWRITEBYTECODE", None)
    if args.simulate:
        out = simulate_startup(args.repeat, Path(args.root).resolve() if args.root else None)
        if args.json:
            Path(args.json).write_text(json.dumps(out, indent=2) + "\n")
        return 0
    global ROOT
    if args.root:
        ROOT = Path(args.root).resolve()
    cmds = commands(other_root=bool(args.root))
    if args.floor:
        cmds |= {k: [sys.executable, "-c", code] for k, code in FLOOR.items()}
    for cmd in cmds.values():  # warm-up: page cache, .pyc files, R's library
        run_once(cmd)
    times: dict[str, dict[str, list[float]]] = {k: {"wall": [], "cpu": []} for k in cmds}
    for _ in range(args.repeat):  # alternate, so drifting machine load hits every command alike
        for name, cmd in cmds.items():
            w, c = run_once(cmd)
            times[name]["wall"].append(w)
            times[name]["cpu"].append(c)
    med = {k: {m: statistics.median(v[m]) for m in ("wall", "cpu")} for k, v in times.items()}
    print(f"{ROOT}: {args.repeat} rounds, {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}, "
          f"byte-code caches {'off' if args.no_bytecode else 'on'}; medians [s]")
    print(f"{'command':28s} {'wall':>8s} {'cpu':>8s}")
    for k, v in med.items():
        print(f"{k:28s} {v['wall']:8.3f} {v['cpu']:8.3f}")
    out = {"rounds": args.repeat, "bytecode": not args.no_bytecode, "median_s": med}
    r = med.get("Rscript rsm fit")
    if r:
        print()
        for k in ("python -m rsm_lrg fit", "rsm-lrg fit", *(FLOOR if args.floor else ())):
            if k in med:
                ratios = {m: statistics.median(a / b for a, b in zip(times[k][m], times["Rscript rsm fit"][m]))
                          for m in ("wall", "cpu")}
                out[f"ratio {k} / R"] = ratios
                verdict = "at or under" if ratios["cpu"] <= 1.5 else "OVER"
                if k in FLOOR:
                    print(f"{k.strip():28s} / R: CPU {ratios['cpu']:.2f}x (floor, not a fit)")
                    continue
                print(f"{k} / R: CPU {ratios['cpu']:.2f}x, wall {ratios['wall']:.2f}x "
                      f"(median of per-round ratios; target CPU <= 1.5x: {verdict})")
    if args.in_process:
        out["in_process"] = in_process(args.repeat)
    h = med.get("rsm-lrg --help") or med.get("python -m rsm_lrg --help")
    if h:
        print(f"rsm-lrg --help: {h['wall']:.3f} s wall (target < 0.15 s: {'met' if h['wall'] < 0.15 else 'NOT met'})")
    if args.json:
        Path(args.json).write_text(json.dumps(out, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
