"""``rsm-lrg loop``: the closed loop with an ``--evaluate`` script of the test's own (a quadratic
whose minimum is known), resumed after the loop is killed mid-round without repeating a
finished evaluation; failing, garbage and hanging commands as one ``error:`` line and exit 2
with the study directory left readable; ``--surrogate`` on two factors of Table 3."""

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest
from _cli_errors import error_line
from _cli_process import cli_env, is_alive

from rsm_lrg.cli import main

#: y = (x1 - 0.3)^2 + 2 (x2 + 0.2)^2 on [-1, 1]^2: minimum 0 at (0.3, -0.2). MODE (argv[3]) makes
#: the command misbehave; LOOP_LOG gets one line per row evaluated, after the output is written;
#: while the file LOOP_HANG exists, the call after the LOOP_AFTER-th logged row writes its pid to
#: LOOP_HANG + ".pid" and sleeps.
SCRIPT = r'''
import csv, os, sys, time
src, dst = sys.argv[1], sys.argv[2]
mode = sys.argv[3] if len(sys.argv) > 3 else "ok"
rows = list(csv.DictReader(open(src)))
log = os.environ.get("LOOP_LOG")
hang = os.environ.get("LOOP_HANG")
done = len(open(log).read().splitlines()) if log and os.path.exists(log) else 0
if mode == "hang" or (hang and os.path.exists(hang) and done >= int(os.environ["LOOP_AFTER"])):
    if hang:
        open(hang + ".pid", "w").write(str(os.getpid()))
    time.sleep(120)
if mode == "fail":
    sys.stderr.write("solver diverged\n")
    sys.exit(3)
if mode == "delete":
    os.remove(src)
if mode == "edit":
    open(src, "a").write("1,1,0,0,0,0\n")
ys = [(float(r["x1"]) - 0.3) ** 2 + 2 * (float(r["x2"]) + 0.2) ** 2 for r in rows]
with open(dst, "w") as f:
    if mode == "garbage":
        f.write("y\n" + "".join("converged?\n" for v in ys))
    elif mode == "empty":
        pass
    elif mode == "short":
        f.write("y\n" + "".join(f"{v!r}\n" for v in ys[:-1]))
    elif mode == "nan":
        f.write("y\n" + "".join("nan\n" for v in ys))
    elif mode == "nocolumn":
        f.write("z\n" + "".join(f"{v!r}\n" for v in ys))
    elif mode != "nooutput":
        f.write("y\n" + "".join(f"{v!r}\n" for v in ys))
if mode == "nooutput":
    os.remove(dst) if os.path.exists(dst) else None
if log:
    with open(log, "a") as fh:
        fh.write("".join(f"{r['x1']},{r['x2']}\n" for r in rows))
'''

BOX = ["--factor", "x1=-1:1", "--factor", "x2=-1:1", "--response", "y"]


@pytest.fixture()
def script(tmp_path):
    p = tmp_path / "quadratic.py"
    p.write_text(SCRIPT)
    return p


def _evaluate(script, mode="ok"):
    return f"{sys.executable} {script} {{in}} {{out}} {mode}"


def test_finds_the_minimum_within_the_budget(tmp_path, script, capsys, monkeypatch):
    log = tmp_path / "log.txt"
    monkeypatch.setenv("LOOP_LOG", str(log))
    study = tmp_path / "study"
    rc = main(["loop", *BOX, "--budget", "11", "--initial", "6", "--batch", "1", "--ei-tol", "0",
               "--evaluate", _evaluate(script), "-o", str(study), "--json", "-"])
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    s = json.loads(cap.out)
    assert s["evaluations"] == 11 and s["stopped_because"] == "budget" and s["rounds"] == 6
    best = s["best"]
    # the quadratic's minimum is 0 at (0.3, -0.2); the 6 LHS runs reach 0.104, the 5 EI runs 0.0051
    assert s["convergence"][5]["best_so_far"] > 0.05
    assert best["observed"] < 0.01 and best["round"] > 0
    assert abs(best["setting"]["x1"] - 0.3) < 0.1 and abs(best["setting"]["x2"] + 0.2) < 0.1
    assert best["pi_low"] <= best["predicted"] <= best["pi_high"]
    # one line per evaluated row: every evaluation ran exactly once
    assert len(log.read_text().splitlines()) == 11
    curve = [c["best_so_far"] for c in s["convergence"]]
    assert len(curve) == 11 and all(a >= b for a, b in zip(curve, curve[1:]))
    man = json.loads((study / "study.json").read_text())
    assert man["status"] == "finished" and man["convergence"] == s["convergence"]
    runs = pd.concat(pd.read_csv(study / f"round_{r:03d}" / "responses.csv") for r in range(6))
    assert runs["evaluation"].tolist() == list(range(1, 12))
    assert (runs["y"] - ((runs.x1 - 0.3) ** 2 + 2 * (runs.x2 + 0.2) ** 2)).abs().max() < 1e-12
    for r in range(1, 6):
        assert (study / f"round_{r:03d}" / "model.json").exists()
        assert json.loads((study / f"round_{r:03d}" / "suggestions.json").read_text())["criterion"] == "ei"
    page = (study / "report.html").read_text()
    assert "Best setting" in page and "data:image/png;base64," in page and "<script" not in page
    assert cap.err.count("loop: round") == 6
    # run again: everything is read back, nothing evaluated
    assert main(["loop", *BOX, "--budget", "11", "--initial", "6", "--batch", "1", "--ei-tol", "0",
                 "--evaluate", _evaluate(script), "-o", str(study), "--no-progress"]) == 0
    assert len(log.read_text().splitlines()) == 11
    # a different option is refused, naming it
    line = error_line(capsys, main(["loop", *BOX, "--budget", "12", "--initial", "6", "--batch", "1", "--ei-tol",
                                    "0", "--evaluate", _evaluate(script), "-o", str(study)]))
    assert "--budget" in line and "differs" in line


def test_length_scale_bounds_are_the_studys(tmp_path, script, capsys, monkeypatch):
    # a new study takes km's upper bound (0.001:2) unless told otherwise and records it; resumed
    # without the option it keeps its own, with another one it is refused naming the option; a
    # study begun before the option existed (no key in study.json) was fitted with 0.001:10
    monkeypatch.setenv("LOOP_LOG", str(tmp_path / "log.txt"))

    def run(study, budget, *extra):
        return main(["loop", *BOX, "--budget", str(budget), "--initial", "6", "--ei-tol", "0", "--evaluate",
                     _evaluate(script), "-o", str(study), "--no-progress", "--json", "-", *extra])

    def used(study, r):
        return json.loads((study / f"round_{r:03d}" / "model.json").read_text())["gp"]["search"]["length_scale_bounds"]

    a, b = tmp_path / "a", tmp_path / "b"
    assert run(a, 7) == 0 and run(b, 7, "--length-scale-bounds", "0.001:10") == 0
    capsys.readouterr()
    options = {s: json.loads((s / "study.json").read_text())["options"]["length_scale_bounds"] for s in (a, b)}
    assert options == {a: [0.001, 2.0], b: [0.001, 10.0]}
    assert used(a, 1) == [0.001, 2.0] and used(b, 1) == [0.001, 10.0]
    line = error_line(capsys, run(a, 7, "--length-scale-bounds", "0.001:10"))
    assert "--length-scale-bounds" in line and "differs" in line
    man = json.loads((b / "study.json").read_text())  # as a study of the previous release wrote it
    del man["options"]["length_scale_bounds"]
    (b / "study.json").write_text(json.dumps(man))
    assert run(b, 7) == 0 and run(b, 7, "--length-scale-bounds", "0.001:10") == 0  # read back
    assert json.loads((b / "study.json").read_text())["options"]["length_scale_bounds"] == [0.001, 10.0]
    capsys.readouterr()
    line = error_line(capsys, run(b, 7, "--length-scale-bounds", "0.001:2"))
    assert "--length-scale-bounds" in line and "'[0.001, 10.0]' there" in line
    assert len((tmp_path / "log.txt").read_text().splitlines()) == 14  # 7 runs a study, none repeated


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_killed_mid_round_resumes_without_repeating(tmp_path, script, sig):
    log, hang = tmp_path / "log.txt", tmp_path / "hang"
    env = dict(cli_env(), LOOP_LOG=str(log), LOOP_HANG=str(hang), LOOP_AFTER="6")
    study = tmp_path / "study"
    args = [sys.executable, "-m", "rsm_lrg", "loop", *BOX, "--budget", "8", "--initial", "5", "--ei-tol", "0",
            "--evaluate", _evaluate(script), "-o", str(study), "--no-progress"]
    hang.write_text("")
    proc = subprocess.Popen(args, env=env, cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    pid_file = Path(str(hang) + ".pid")
    end = time.monotonic() + 120
    while not pid_file.exists() and proc.poll() is None and time.monotonic() < end:
        time.sleep(0.05)
    assert pid_file.exists(), proc.communicate()
    time.sleep(0.2)
    child = int(pid_file.read_text())
    # the loop hangs inside round 2 (rounds 0 and 1 finished: 5 + 1 rows logged)
    assert len(log.read_text().splitlines()) == 6
    assert (study / "round_002" / "design.csv").exists() and not (study / "round_002" / "responses.csv").exists()
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=60)
    assert proc.returncode in (-9, 128 + sig), (proc.returncode, err)
    if sig == signal.SIGTERM:
        assert err.strip().splitlines() == ["error: terminated by SIGTERM; no output written"]
    end = time.monotonic() + 10
    while is_alive(child) and time.monotonic() < end:  # the command dies with the loop
        time.sleep(0.05)
    assert not is_alive(child)
    before = (study / "round_000" / "responses.csv").read_bytes()
    hang.unlink()
    done = subprocess.run(args + ["--json", "-"], env=env, cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    s = json.loads(done.stdout)
    assert s["resumed"] and s["evaluations"] == 8
    assert len(log.read_text().splitlines()) == 8  # the 6 finished evaluations were not run again
    assert (study / "round_000" / "responses.csv").read_bytes() == before
    assert not list(study.rglob(".rsm-lrg-loop.*"))


@pytest.mark.parametrize("mode, words", [
    ("fail", ["round 0", "exited with status 3", "solver diverged"]),
    ("garbage", ["round 0", "wrote 'converged?' in column 'y', row 1"]),
    ("empty", ["round 0", "not a CSV table"]),
    ("short", ["round 0", "4 row(s) for 5 design row(s)"]),
    ("nan", ["round 0", "wrote nan", "finite number"]),
    ("nocolumn", ["round 0", "no column 'y'"]),
    ("nooutput", ["round 0", "no output file"]),
    ("delete", ["round 0", "deleted its input"]),
    ("edit", ["round 0", "changed its input"]),
    ("hang", ["round 0", "--evaluate-timeout 1 s"]),
])
def test_a_bad_command_is_one_error_line(mode, words, tmp_path, script, capsys):
    study = tmp_path / "study"
    t0 = time.monotonic()
    rc = main(["loop", *BOX, "--budget", "6", "--initial", "5", "--evaluate", _evaluate(script, mode),
               "--evaluate-timeout", "1", "-o", str(study), "--no-progress"])
    line = error_line(capsys, rc)
    for w in words:
        assert w in line, line
    assert time.monotonic() - t0 < 60
    man = json.loads((study / "study.json").read_text())  # consistent: readable, nothing recorded as run
    assert man["status"] == "running" and man["rounds"] == []
    assert (study / "round_000" / "design.csv").exists() and not (study / "round_000" / "responses.csv").exists()
    assert not list(study.rglob(".rsm-lrg-loop.*"))


@pytest.mark.parametrize("args, words", [
    (["--evaluate", "python x.py {in}"], ["--evaluate", "{out}"]),
    (["--evaluate", "no-such-program-here {in} {out}"], ["round 0", "cannot start", "no-such-program-here"]),
    (["--surrogate", "--factor", "x3=0:1"], ["--factor", "x3"]),
    (["--surrogate", "--initial", "9"], ["--initial"]),
    (["--surrogate", "--goal", "sideways"], ["--goal"]),
])
def test_bad_options(args, words, tmp_path, capsys):
    base = ["--factor", "velocity_m_s=0.4:0.6", "--response", "tcr_c_per_min", "--budget", "6"]
    rc = main(["loop", *base, *args, "-o", str(tmp_path / "s"), "--no-progress"])
    line = error_line(capsys, rc)
    for w in words:
        assert w in line, line


def test_not_a_study_directory(tmp_path, capsys):
    d = tmp_path / "d"
    d.mkdir()
    (d / "mine.txt").write_text("x")
    line = error_line(capsys, main(["loop", *BOX, "--budget", "6", "--evaluate", "x {in} {out}", "-o", str(d)]))
    assert "not an rsm-lrg loop study" in line
    assert (d / "mine.txt").read_text() == "x" and len(list(d.iterdir())) == 1


def test_surrogate_on_two_factors_of_table3(tmp_path, capsys):
    study = tmp_path / "s"
    rc = main(["loop", "--factor", "velocity_m_s=0.4:0.6", "--factor", "acceleration_m_s2=20:40",
               "--response", "tcr_c_per_min", "--goal", "minimize", "--budget", "9", "--initial", "5",
               "--surrogate", "-o", str(study), "--json", "-", "--no-progress"])
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    s = json.loads(cap.out)
    # the rate falls towards the slow corner (0.4 m/s, 20 m/s^2): round 1 runs it; rounds 2 and 3
    # try the rest of the slow edge (0.4 m/s, 40 and about 22 m/s^2), and then the largest
    # expected improvement is below 1e-6 of the range: the loop stops with a run to spare
    assert s["evaluations"] == 8 and s["rounds"] == 4 and s["stopped_because"] == "ei-tol"
    assert s["best"]["setting"] == {"velocity_m_s": 0.4, "acceleration_m_s2": 20.0}
    assert s["best"]["round"] == 1
    nxt = json.loads((study / "round_004" / "suggestions.json").read_text())
    assert nxt["runs"][0]["criterion"] <= s["ei_tol"]["absolute"] == pytest.approx(
        1e-6 * (max(c["value"] for c in s["convergence"]) - min(c["value"] for c in s["convergence"])))
    runs = pd.concat(pd.read_csv(study / f"round_{r:03d}" / "responses.csv") for r in range(4))
    # the surrogate itself at the same settings (stroke and thickness at the parameter file's values)
    import rsm_lrg

    design = runs[["velocity_m_s", "acceleration_m_s2"]].assign(thickness_m=3e-4, stroke_m=0.075)
    direct = rsm_lrg.simulate(design, noise_sd=0.0, seed=0)["tcr_c_per_min"].to_numpy()
    assert abs(runs["tcr_c_per_min"].to_numpy() - direct).max() < 1e-15
    assert s["best"]["observed"] == runs["tcr_c_per_min"].min()


def test_batches_in_pieces_on_two_workers(tmp_path, script, capsys, monkeypatch):
    log = tmp_path / "log.txt"
    monkeypatch.setenv("LOOP_LOG", str(log))
    study = tmp_path / "study"
    rc = main(["loop", *BOX, "--goal", "target=0.5", "--budget", "8", "--initial", "4", "--batch", "2",
               "--workers", "2", "--ei-tol", "0", "--evaluate", _evaluate(script), "-o", str(study), "--json", "-",
               "--no-progress"])
    cap = capsys.readouterr()
    assert rc == 0, cap.err
    s = json.loads(cap.out)
    assert s["rounds"] == 3 and s["evaluations"] == 8 and s["goal"] == "target"
    assert len(log.read_text().splitlines()) == 8
    r1 = pd.read_csv(study / "round_001" / "responses.csv")
    assert len(r1) == 2 and not (study / "round_001" / "rows").exists()
    assert abs(s["best"]["observed"] - 0.5) == min(abs(c["value"] - 0.5) for c in s["convergence"])


def test_surrogate_rounds_on_a_dask_scheduler_equal_this_process(tmp_path, capsys):
    """``--scheduler`` (with ``--surrogate``): each round's rows run on a real local Dask cluster
    and the study is the one run in this process (the rows do not depend on where they run)."""
    distributed = pytest.importorskip("distributed")
    argv = ["loop", "--factor", "velocity_m_s=0.4:0.6", "--response", "tcr_c_per_min", "--goal", "minimize",
            "--budget", "5", "--initial", "4", "--ei-tol", "0", "--surrogate", "--json", "-", "--no-progress"]
    assert main([*argv, "-o", str(tmp_path / "here")]) == 0
    here = json.loads(capsys.readouterr().out)
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        # as a process: an event loop left running in this one (a browser test's) would stop the client
        done = subprocess.run([sys.executable, "-m", "rsm_lrg", *argv, "-o", str(tmp_path / "dask"), "--scheduler",
                               cluster.scheduler_address], capture_output=True, text=True, env=cli_env(), timeout=600)
    assert done.returncode == 0, done.stderr
    there = json.loads(done.stdout)
    assert {k: v for k, v in there.items() if k != "study"} == {k: v for k, v in here.items() if k != "study"}
    for name in ("round_000/responses.csv", "round_001/responses.csv"):
        assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "here" / name).read_bytes()


def test_scheduler_is_only_for_the_surrogate(tmp_path, capsys):
    line = error_line(capsys, main(["loop", *BOX, "--budget", "6", "--evaluate", "x {in} {out}",
                                    "--scheduler", "tcp://127.0.0.1:9", "-o", str(tmp_path / "s")]))
    assert "--scheduler" in line and "--surrogate" in line
