"""The README's virtual-run workflow, run exactly as printed (design -> simulate -> fit ->
optimize) as real processes: the fit finds the design's four factors without --factor."""

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

FACTORS = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
README = Path(__file__).resolve().parents[2] / "README.md"


def readme_commands() -> list[str]:
    """The ``rsm-lrg`` commands of the README's "Virtual runs" block, as printed (line
    continuations joined, comments dropped, the program name removed)."""
    text = README.read_text(encoding="utf-8")
    block = re.search(r"^### Virtual runs.*?^```bash\n(.*?)^```", text, re.S | re.M).group(1)
    lines = block.replace("\\\n", " ").splitlines()
    cmds = [shlex.split(line, comments=True) for line in lines]
    return [" ".join(c[1:]) for c in cmds if c and c[0] == "rsm-lrg"]


COMMANDS = readme_commands()


def test_the_readme_block_is_design_simulate_fit_optimize():
    assert [c.split()[0] for c in COMMANDS] == ["design", "simulate", "fit", "optimize"]
    assert "--factor" not in COMMANDS[2]  # the fit finds the factors itself


def _run(cmd, cwd):
    return subprocess.run([sys.executable, "-m", "rsm_lrg", *cmd.split()], cwd=cwd, capture_output=True, text=True)


@pytest.mark.slow
def test_design_simulate_fit_optimize_as_printed(tmp_path):
    outs = []
    for cmd in COMMANDS:
        res = _run(cmd, tmp_path)
        assert res.returncode == 0, (cmd, res.stderr)
        outs.append(res)
    fit_out = outs[2].stdout
    assert all(name in outs[3].stdout for name in FACTORS)  # the optimum names the four factors
    assert "runs: 27" in fit_out
    for letter, name in zip("ABCD", FACTORS):
        assert f"  {letter}: {name} " in fit_out, fit_out[:800]
    # the text output says which columns were taken as factors and which were left out
    assert "Factors taken from the design's coded columns" in fit_out
    assert "Numeric columns left out" in fit_out and "steady_rise_k" in fit_out

    res = _run("fit runs.csv --response tcr_c_per_min --json -", tmp_path)
    assert res.returncode == 0, res.stderr
    d = json.loads(res.stdout)
    # the design's levels (BBD: every factor at -1, 0, +1), as written by `design`
    assert [(f["name"], f["low"], f["high"]) for f in d["factors"]] == [
        ("thickness_m", 0.0001, 0.0005), ("stroke_m", 0.04, 0.06), ("velocity_m_s", 0.4, 0.6),
        ("acceleration_m_s2", 20.0, 40.0)]
    assert d["n"] == 27 and len(d["coefficients"]["coded"]) == 15
    assert "note: Factors taken from the design's coded columns" in res.stderr

    res = _run("optimize runs.csv --response tcr_c_per_min --goal minimize --json -", tmp_path)
    assert res.returncode == 0, res.stderr
    opt = json.loads(res.stdout)
    assert list(opt["actual"]) == FACTORS
