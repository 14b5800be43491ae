"""The study directory and the rounds of ``rsm-lrg loop`` (the closed loop evaluate -> fit a
Gaussian process -> suggest -> evaluate ...).

Layout of ``STUDY_DIR`` (every file written atomically: a temporary file renamed into place)::

    study.json                  the manifest: options, rounds, convergence curve, best setting
    round_000/design.csv        the initial space-filling design (a Latin hypercube)
    round_000/responses.csv     its runs: ``evaluation``, ``round``, the factors, the response
    round_001/model.json        the GP fitted to every run before round 1
    round_001/suggestions.json  what ``suggest`` chose (expected improvement, Kriging Believer)
    round_001/design.csv        those settings as a design CSV
    round_001/responses.csv     ...
    round_001/rows/ROWS.csv     pieces of a round already evaluated (``--workers``), kept until
                                the round's responses.csv is written
    final_model.json            the GP fitted to every run, at the end
    report.html                 the best setting, the convergence curve, the model's LOO check

A round is finished when its ``responses.csv`` exists; a design is fixed once its
``design.csv`` exists. Resuming reads everything back from the files (never from memory),
so an interrupted and resumed study computes exactly what an uninterrupted one does, and
no finished evaluation (a finished round, or a finished piece of one) runs again.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import math
import os
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..io import InputError, quote_user_value

__all__ = ["LoopOptions", "run_study", "MANIFEST", "FORMAT", "compared_options", "surrogate_factor_names"]

MANIFEST = "study.json"
FORMAT = "rsm-lrg loop study"
VERSION = 1
#: Options that fix what the study computes: a resumed study must be given the same values.
compared_options = ("factors", "response", "goal", "budget", "initial", "batch", "seed", "evaluator",
                    "ei_tol", "kernel", "trend", "length_scale_bounds")
#: What a study's manifest written before an option existed stands for: the GP's length-scale
#: bounds were then ``fit``'s (``THETA_BOUNDS``, 1e-3 and 10 times the range).
_BEFORE_OPTION = {"length_scale_bounds": [1e-3, 10.0]}
_TMP_PREFIX = ".rsm-lrg-loop."


@dataclass
class LoopOptions:
    """The options of a study (those of :data:`compared_options` are recorded in the manifest)."""

    factors: list[str]
    response: str
    goal: str
    budget: int
    initial: int
    batch: int
    seed: int
    evaluator: dict
    ei_tol: float
    kernel: str
    trend: str
    #: The GP's length-scale bounds, multiples of each factor's range (``--length-scale-bounds``);
    #: None: a new study takes ``LOOP_THETA_BOUNDS`` (R ``km``'s upper bound), a resumed one its own.
    length_scale_bounds: list[float] | None = None
    workers: int = 1
    timeout: float = 600.0
    progress: bool = True
    extra: dict = field(default_factory=dict)
    #: Where ``--surrogate`` runs its rows (a Dask ``Client.get_executor()`` with
    #: ``--scheduler``; None: this process). Not recorded: the rows do not depend on it.
    executor: Any = None

    def recorded(self) -> dict:
        return {k: getattr(self, k) for k in compared_options}


# --- files ----------------------------------------------------------------------------------

def _write_atomic(path: Path, text: str) -> None:
    """``text`` to ``path``: a temporary file in the same directory, synced, renamed over it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=_TMP_PREFIX, suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(text.encode("utf-8"))
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _json_text(obj: Any) -> str:
    from ..io import to_jsonable

    return json.dumps(to_jsonable(obj), indent=2, allow_nan=False) + "\n"


def _clean_leftovers(root: Path) -> None:
    """Temporary files and scratch directories of an interrupted run."""
    for p in root.rglob(f"{_TMP_PREFIX}*"):
        with contextlib.suppress(OSError):
            if p.is_dir() and not p.is_symlink():
                shutil.rmtree(p)
            else:
                p.unlink()


def _round_dir(root: Path, r: int) -> Path:
    return root / f"round_{r:03d}"


# --- the surrogate ---------------------------------------------------------------------------

def surrogate_factor_names() -> tuple[tuple[str, ...], dict[str, float]]:
    """The factors ``--surrogate`` can vary (the design columns and per-row parameters of
    ``rsm_lrg.simulate``) and the defaults of the four design columns (the parameter file's
    values: hinge thickness, stroke, velocity, acceleration)."""
    from ..physics.params import LRGParams, param_names
    from ..surrogate.design_input import FACTOR_COLUMNS

    p = LRGParams()
    defaults = {"thickness_m": float(p.hinge_thickness_m), "stroke_m": float(p.stroke_m),
                "velocity_m_s": float(p.velocity_m_s), "acceleration_m_s2": float(p.acceleration_m_s2)}
    per_row = [n for n in param_names() if n not in ("hinge_thickness_m", "heat_in_calories", "hinge_membrane",
                                                      *defaults)]
    return (*FACTOR_COLUMNS, *per_row), defaults


def _surrogate(design: Any, response: str, executor: Any = None) -> Any:
    """The calibrated, deterministic surrogate (noise 0) at the design's rows: the response
    (on ``executor``'s workers when one is given; the same numbers)."""
    from ..surrogate.execute import simulate

    _, defaults = surrogate_factor_names()
    df = design.copy()
    for name, value in defaults.items():
        if name not in df.columns:
            df[name] = value
    out = simulate(df, seed=0, noise_sd=0.0, calibration="default", progress=False, executor=executor)
    return out[response].to_numpy(dtype=float)


# --- the --evaluate command -------------------------------------------------------------------

class EvaluateError(InputError):
    """A failed evaluation (one line for the user)."""


def _command(template: str, src: Path, dst: Path) -> list[str]:
    return [a.replace("{in}", str(src)).replace("{out}", str(dst)) for a in shlex.split(template)]


def _die_with_parent() -> None:  # pragma: no cover - runs in the child
    """Child set-up: its own process group (a timeout kills the command and its children),
    and Linux's PR_SET_PDEATHSIG so that it dies when the loop is killed (SIGKILL)."""
    if sys.platform.startswith("linux"):
        with contextlib.suppress(OSError, AttributeError):
            import ctypes

            ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL), 0, 0, 0)


def _kill_group(proc: subprocess.Popen) -> None:
    with contextlib.suppress(OSError):
        os.killpg(proc.pid, signal.SIGKILL)
    with contextlib.suppress(Exception):
        proc.wait(5)


def _tail(path: Path, n: int = 120) -> str:
    try:
        text = path.read_bytes()[-2000:].decode("utf-8", "replace")
    except OSError:
        return ""
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    return (" (its last line: " + quote_user_value(lines[-1], n) + ")") if lines else ""


def _read_piece_output(path: Path, response: str, n: int, what: str) -> Any:
    import numpy as np
    import pandas as pd

    if not path.exists():
        raise EvaluateError(f"{what} wrote no output file {{out}}")
    try:
        df = pd.read_csv(path)
    except Exception as exc:  # empty, binary, ragged: the command's fault
        raise EvaluateError(f"{what} wrote an output that is not a CSV table ({type(exc).__name__})") from None
    if response not in df.columns:
        cols = ", ".join(quote_user_value(c, 20) for c in list(df.columns)[:5]) or "none"
        raise EvaluateError(f"{what} wrote no column {quote_user_value(response)} (columns: {cols})")
    if len(df) != n:
        raise EvaluateError(f"{what} wrote {len(df)} row(s) for {n} design row(s); one per row is needed")
    values = pd.to_numeric(df[response], errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        i = int(bad[0])
        raise EvaluateError(f"{what} wrote {quote_user_value(df[response].iloc[i])} in column "
                            f"{quote_user_value(response)}, row {i + 1}; a finite number is needed")
    return values


@dataclass
class _Running:
    rows: list[int]
    proc: subprocess.Popen
    src: Path
    dst: Path
    digest: str
    err: Path
    start: float


def _finished(r: _Running, status: int, label: str, response: str, done: Any) -> None:
    """Check a call that ended (status, its input untouched, its output) and keep its values."""
    if status != 0:
        how = f"was killed by signal {-status}" if status < 0 else f"exited with status {status}"
        raise EvaluateError(f"{label} {how}{_tail(r.err)}")
    try:
        same = hashlib.sha256(r.src.read_bytes()).hexdigest() == r.digest
    except OSError:
        raise EvaluateError(f"{label} deleted its input design {{in}}; the study keeps its own "
                            "copy, but a command that removes its input is not trusted") from None
    if not same:
        raise EvaluateError(f"{label} changed its input design {{in}}; the study keeps its own "
                            "copy, but a command that edits its input is not trusted")
    done(r.rows, _read_piece_output(r.dst, response, len(r.rows), label))


def _evaluate_command(template: str, design_csv: str, rows: list[int], response: str, work: Path,
                      workers: int, timeout: float, what: str, done: Any) -> None:
    """Run the command on pieces of the design (``rows``, at most ``workers`` at a time); call
    ``done(rows, values)`` as each piece finishes."""
    header, *lines = design_csv.splitlines()
    k = max(1, min(workers, len(rows)))
    size = math.ceil(len(rows) / k)
    pieces = [rows[i:i + size] for i in range(0, len(rows), size)]
    waiting = list(pieces)
    running: list[_Running] = []
    try:
        while waiting or running:
            while waiting and len(running) < k:
                piece = waiting.pop(0)
                d = Path(tempfile.mkdtemp(prefix=_TMP_PREFIX, dir=work))
                src, dst, err = d / "design.csv", d / "responses.csv", d / "stderr.txt"
                text = "\n".join([header, *(lines[i] for i in piece)]) + "\n"
                src.write_text(text, encoding="utf-8")
                argv = _command(template, src, dst)
                try:
                    with open(err, "wb") as eh:
                        proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                                stderr=eh, cwd=os.getcwd(), start_new_session=True,
                                                preexec_fn=_die_with_parent)
                except OSError as exc:
                    raise EvaluateError(f"{what}: cannot start the --evaluate command "
                                        f"{quote_user_value(argv[0])}: {exc.strerror or type(exc).__name__}") from None
                running.append(_Running(piece, proc, src, dst, hashlib.sha256(text.encode()).hexdigest(), err,
                                        time.monotonic()))
            time.sleep(0.01)
            for r in list(running):
                label = f"{what}, rows {r.rows[0] + 1}-{r.rows[-1] + 1}: the --evaluate command"
                status = r.proc.poll()
                if status is None:
                    if time.monotonic() - r.start > timeout:
                        _kill_group(r.proc)
                        raise EvaluateError(f"{label} ran past --evaluate-timeout {timeout:g} s and was stopped")
                    continue
                running.remove(r)
                try:
                    _finished(r, status, label, response, done)
                finally:
                    shutil.rmtree(r.src.parent, ignore_errors=True)
    finally:
        for r in running:
            _kill_group(r.proc)
            shutil.rmtree(r.src.parent, ignore_errors=True)


# --- the study -------------------------------------------------------------------------------

def _goal_best(kind: str, target: float | None, y: Any) -> int:
    import numpy as np

    y = np.asarray(y, dtype=float)
    if kind == "minimize":
        return int(np.argmin(y))
    if kind == "maximize":
        return int(np.argmax(y))
    assert target is not None
    return int(np.argmin(np.abs(y - target)))


class Study:
    """One study directory: its manifest, its rounds, and the runs read back from the files."""

    def __init__(self, root: Path, opts: LoopOptions):
        from ..design.core import as_factor_space
        from ..model.build.goals import parse_goal

        self.root = root
        self.opts = opts
        self.space = as_factor_space(opts.factors)
        self.names = [f.name for f in self.space.factors]
        self.kind, self.target = parse_goal(opts.goal)
        self.rounds: list[dict] = []
        self.stopped: str | None = None

    # manifest
    def open(self) -> bool:
        """Create the directory or check the manifest of an existing one; True when resuming."""
        root = self.root
        if root.exists() and not root.is_dir():
            raise InputError(f"-o/--output {root}: exists and is not a directory")
        manifest = root / MANIFEST
        if root.is_dir() and not manifest.exists():
            if any(root.iterdir()):
                raise InputError(f"-o/--output {root}: a directory that is not an rsm-lrg loop study (no "
                                 f"{MANIFEST}) and not empty; give a new or empty directory")
        if not manifest.exists():
            if self.opts.length_scale_bounds is None:
                from ..model.pipelines.gp import LOOP_THETA_BOUNDS

                self.opts.length_scale_bounds = list(LOOP_THETA_BOUNDS)
            root.mkdir(parents=True, exist_ok=True)
            self._save()
            return False
        try:
            old = json.loads(manifest.read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:
            raise InputError(f"{manifest}: not a readable study manifest ({type(exc).__name__})") from None
        if not isinstance(old, dict) or old.get("format") != FORMAT or not isinstance(old.get("options"), dict):
            raise InputError(f"{manifest}: not an rsm-lrg loop study manifest")
        was = dict(_BEFORE_OPTION, **old["options"])
        if self.opts.length_scale_bounds is None:  # not given: the study's own
            self.opts.length_scale_bounds = was["length_scale_bounds"]
        now = self.opts.recorded()
        for key in compared_options:
            if json.loads(json.dumps(now[key])) != was.get(key):
                opt = _OPTION_OF[key]
                raise InputError(f"{opt}: differs from the study in {root} ({_shown(was.get(key))} there, "
                                 f"{_shown(now[key])} now); resume with the same options or give a new -o")
        _clean_leftovers(root)
        return True

    def _save(self, **extra: Any) -> None:
        doc = {"format": FORMAT, "version": VERSION, "options": self.opts.recorded(),
               "status": "finished" if self.stopped else "running", "stopped_because": self.stopped,
               "rounds": self.rounds, **extra}
        _write_atomic(self.root / MANIFEST, _json_text(doc))

    def _progress(self, text: str) -> None:
        if self.opts.progress:
            print(text, file=sys.stderr, flush=True)

    # runs
    def _responses(self, r: int) -> Any:
        import pandas as pd

        return pd.read_csv(_round_dir(self.root, r) / "responses.csv")

    def runs(self) -> Any:
        import pandas as pd

        frames = [self._responses(r["round"]) for r in self.rounds]
        if not frames:
            return pd.DataFrame(columns=["evaluation", "round", *self.names, self.opts.response])
        return pd.concat(frames, ignore_index=True)

    def _fit(self, data: Any) -> Any:
        from ..model import fit

        # by default km's upper length-scale bound (2 x the range), as DiceOptim's EGO: LOOP_THETA_BOUNDS
        bounds = self.opts.length_scale_bounds
        assert bounds is not None  # resolved by open(): given, the study's, or LOOP_THETA_BOUNDS
        return fit(data[[*self.names, self.opts.response]], self.opts.response, factors=self.opts.factors,
                   model="gp", kernel=self.opts.kernel, trend=self.opts.trend, seed=self.opts.seed,
                   length_scale_bounds=(float(bounds[0]), float(bounds[1])))

    def _design(self, r: int, done: int) -> tuple[str, dict]:
        """Round ``r``'s design CSV (made, or read back) and what the round records."""
        d = _round_dir(self.root, r)
        path = d / "design.csv"
        info: dict = {"round": r, "design": f"{d.name}/design.csv", "responses": f"{d.name}/responses.csv"}
        if r == 0:
            info["kind"] = "initial"
            if not path.exists():
                from ..design.spacefill import latin_hypercube

                design = latin_hypercube(self.space, self.opts.initial, seed=self.opts.seed)
                _write_atomic(path, design.csv_text())
            return path.read_text(encoding="utf-8"), info
        info.update(kind="suggested", model=f"{d.name}/model.json", suggestions=f"{d.name}/suggestions.json")
        sugg_path = d / "suggestions.json"
        if not path.exists() or not sugg_path.exists():
            from ..optimize.next_runs import suggest

            data = self.runs()
            model = self._fit(data)
            q = min(self.opts.batch, self.opts.budget - done)
            s = suggest(model, self.opts.goal, q, criterion="ei", seed=self.opts.seed + r)
            _write_atomic(d / "model.json", _json_text(model.to_dict()))
            _write_atomic(sugg_path, _json_text(s.to_dict()))
            _write_atomic(path, s.design.csv_text())
        sugg = json.loads(sugg_path.read_text(encoding="utf-8"))
        info["max_ei"] = float(sugg["runs"][0]["criterion"])
        return path.read_text(encoding="utf-8"), info

    def _stop_by_ei(self, done: int) -> bool:
        """Fit, and stop when the largest expected improvement is below ``ei_tol`` times the
        range of the responses (the round's suggestions are kept either way)."""
        import numpy as np

        y = self.runs()[self.opts.response].to_numpy(dtype=float)
        if self.opts.ei_tol <= 0 or done >= self.opts.budget:
            return False
        _, info = self._design(len(self.rounds), done)
        span = float(np.ptp(y))
        return info["max_ei"] <= self.opts.ei_tol * span

    def _evaluate(self, r: int, design_csv: str, what: str) -> Any:
        """The response at every row of round ``r`` (pieces already evaluated are read back)."""
        import io

        import numpy as np
        import pandas as pd

        design = pd.read_csv(io.StringIO(design_csv))
        n = len(design)
        values = np.full(n, np.nan)
        d = _round_dir(self.root, r)
        pieces = d / "rows"
        if pieces.is_dir():
            for p in sorted(pieces.glob("rows_*.csv")):
                got = pd.read_csv(p)
                values[got["row"].to_numpy(dtype=int)] = got[self.opts.response].to_numpy(dtype=float)
        todo = [i for i in range(n) if not np.isfinite(values[i])]
        ev = self.opts.evaluator
        if todo and ev["kind"] == "surrogate":
            try:
                values[todo] = _surrogate(design.iloc[todo][self.names].reset_index(drop=True), self.opts.response,
                                          self.opts.executor)
            except ValueError as exc:
                raise EvaluateError(f"{what}: the surrogate: {exc}") from None
            if not np.isfinite(values).all():
                i = int(np.flatnonzero(~np.isfinite(values))[0])
                raise EvaluateError(f"{what}, row {i + 1}: the surrogate gave no finite {self.opts.response} there")
        elif todo:
            def keep(rows: list[int], v: Any) -> None:
                values[rows] = v
                piece = pd.DataFrame({"row": rows, self.opts.response: v})
                _write_atomic(pieces / f"rows_{rows[0]:05d}-{rows[-1]:05d}.csv", piece.to_csv(index=False))

            _evaluate_command(ev["command"], design_csv, todo, self.opts.response, d, self.opts.workers,
                              self.opts.timeout, what, keep)
        out = pd.DataFrame({"evaluation": np.arange(n) + 1 + sum(x["runs"] for x in self.rounds),
                            "round": r, **{c: design[c].to_numpy() for c in self.names},
                            self.opts.response: values})
        _write_atomic(d / "responses.csv", out.to_csv(index=False, float_format="%.17g"))
        shutil.rmtree(pieces, ignore_errors=True)
        return out

    def run(self) -> dict:
        resumed = self.open()
        done = 0
        r = 0
        self.rounds = []
        while True:
            d = _round_dir(self.root, r)
            if done >= self.opts.budget:
                self.stopped = "budget"
                break
            what = f"round {r}"
            try:
                if r > 0 and self._stop_by_ei(done):
                    self.stopped = "ei-tol"
                    break
                design_csv, info = self._design(r, done)
            except (ValueError, ArithmeticError) as exc:
                raise InputError(f"{what}: the Gaussian process or the search failed: {exc}") from None
            if (d / "responses.csv").exists():
                out = self._responses(r)
                again = True
            else:
                out = self._evaluate(r, design_csv, what)
                again = False
            info["runs"] = len(out)
            self.rounds.append(info)
            done += len(out)
            self._save(evaluations=done)
            best = self._best_line()
            ei = f", largest EI {info['max_ei']:.4g}" if "max_ei" in info else ""
            self._progress(f"loop: round {r} {'read back' if again else 'evaluated'}: {len(out)} run(s), "
                           f"{done}/{self.opts.budget} evaluations{ei}; best {best}")
            r += 1
        return self._finish(resumed)

    def _best_line(self) -> str:
        data = self.runs()
        y = data[self.opts.response].to_numpy(dtype=float)
        i = _goal_best(self.kind, self.target, y)
        at = ", ".join(f"{c}={data[c].iloc[i]:.6g}" for c in self.names)
        return f"{self.opts.response} = {y[i]:.6g} at {at}"

    def _finish(self, resumed: bool) -> dict:
        import numpy as np

        data = self.runs()
        y = data[self.opts.response].to_numpy(dtype=float)
        curve = []
        for k in range(len(y)):
            j = _goal_best(self.kind, self.target, y[:k + 1])
            curve.append({"evaluation": k + 1, "round": int(data["round"].iloc[k]), "value": float(y[k]),
                          "best_so_far": float(y[j])})
        try:
            model = self._fit(data)
        except (ValueError, ArithmeticError) as exc:
            raise InputError(f"the final Gaussian process failed: {exc}") from None
        i = _goal_best(self.kind, self.target, y)
        setting = {c: float(data[c].iloc[i]) for c in self.names}
        p = model.predict(data.iloc[[i]][self.names], interval="prediction")
        loo = model.loo
        best = {"evaluation": int(data["evaluation"].iloc[i]), "round": int(data["round"].iloc[i]),
                "setting": setting, "observed": float(y[i]), "predicted": float(p["predicted"].iloc[0]),
                "se_fit": float(p["se_fit"].iloc[0]), "pi_low": float(p["pi_low"].iloc[0]),
                "pi_high": float(p["pi_high"].iloc[0]), "level": 0.95}
        _write_atomic(self.root / "final_model.json", _json_text(model.to_dict()))
        summary = {"study": str(self.root), "response": self.opts.response, "goal": self.kind, "target": self.target,
                   "evaluations": int(len(y)), "budget": self.opts.budget, "rounds": len(self.rounds),
                   "stopped_because": self.stopped, "resumed": resumed, "best": best,
                   "loo": {"q2": float(loo.q2), "rmse": float(loo.rmse)},
                   "ei_tol": {"relative": self.opts.ei_tol, "absolute": self.opts.ei_tol * float(np.ptp(y))},
                   "convergence": curve, "model": "final_model.json", "report": "report.html"}
        self._save(evaluations=int(len(y)), best=best, convergence=curve, loo=summary["loo"], report="report.html")
        from ..report.loop_page import loop_html

        _write_atomic(self.root / "report.html", loop_html(summary, self.names, list(model.notes)))
        return summary


def _shown(v: Any) -> str:
    return quote_user_value(json.dumps(v) if not isinstance(v, str) else v, 60)


_OPTION_OF = {"factors": "--factor", "response": "--response", "goal": "--goal", "budget": "--budget",
              "initial": "--initial", "batch": "--batch", "seed": "--seed", "evaluator": "--surrogate/--evaluate",
              "ei_tol": "--ei-tol", "kernel": "--kernel", "trend": "--trend",
              "length_scale_bounds": "--length-scale-bounds"}


def run_study(root: Path, opts: LoopOptions) -> dict:
    """Run (or resume) the study in ``root``; returns the summary (also in ``study.json``)."""
    return Study(root, opts).run()
