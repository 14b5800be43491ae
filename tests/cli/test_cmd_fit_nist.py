"""``rsm-lrg fit --terms ... [--no-intercept] --json -`` on every NIST StRD linear regression
set (issue 21): actual-unit coefficients, their standard errors and the residual SD are at
least as accurate as R ``lm`` (R 4.2.2; ``tests/model/r/nist_lm.R`` and its kept output), or,
where R lands nearer the certified 15-digit decimal than that decimal can judge, at least its
resolution; never below 13.5 correct digits.

The data files are NIST's own (``tests/model/data/nist/``); the CSV the command reads holds the
values as written in them (Python writes the shortest decimal that reads back as the double).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from rsm_lrg.cli import main

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "model"))
from test_nist_strd import SETS, _certified_value, load_nist, lre, r_lre, resolution  # noqa: E402


@pytest.fixture(scope="module")
def r_reference():
    return r_lre()


@pytest.mark.parametrize("name", SETS)
def test_cli_fit_of_every_nist_set_is_as_accurate_as_r(name, r_reference, tmp_path, capsys):
    data, cert, terms, intercept = load_nist(name)
    path = tmp_path / f"{name}.csv"
    data.to_csv(path, index=False)
    factors = [c for c in data.columns if c != "y"]
    args = ["fit", str(path), "--response", "y", "--terms", " ".join(terms), "--json", "-"]
    for f in factors:
        args += ["--factor", f]
    if not intercept:
        args.append("--no-intercept")
    assert main(args) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["intercept"] is intercept and d["terms"] == terms
    names = [k for k in cert if k != "sd"]
    worse = []
    for i, term in enumerate(names):
        q = "B" + str(i + (0 if intercept else 1))
        for kind, got in (("coef", d["coefficients"]["actual"][term]), ("se", d["std_errors"]["actual"][term])):
            v = lre(got, _certified_value(cert, q, kind))
            bar = min(r_reference[(name, q, kind)], resolution(_certified_value(cert, q, kind)))
            if v < bar:
                worse.append(f"{term} {kind}: {v:.2f} < {bar:.2f}")
            assert v >= 13.5, f"{name} {term} {kind}: {v:.2f} digits"
    v = lre(d["statistics"]["std_dev"], cert["sd"])
    bar = min(r_reference[(name, "sd", "sd")], resolution(cert["sd"]))
    if v < bar:
        worse.append(f"residual SD: {v:.2f} < {bar:.2f}")
    assert not worse, f"{name}: " + "; ".join(worse)


def test_no_intercept_model_passes_through_the_actual_origin(capsys, tmp_path):
    """NoInt1 is y = b x in actual units: the fit's factor is coded about zero, and the
    prediction at x = 0 is 0 (a coding about the centre would hide an intercept)."""
    import rsm_lrg

    data, cert, terms, _ = load_nist("NoInt1")
    r = rsm_lrg.fit(data, "y", factors=["x"], terms=terms, intercept=False)
    f = r.space.factors[0]
    assert f.center == 0.0
    assert float(r.predict({"x": [0.0]})["predicted"].iloc[0]) == 0.0
    assert r.anova["source"].iloc[-1] == "Uncor Total" and int(r.anova["df"].iloc[-1]) == len(data)
