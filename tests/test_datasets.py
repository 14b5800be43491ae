"""The shipped package data equal the repository's data/ files, and load."""

from pathlib import Path

import pytest

from rsm_lrg import datasets

ROOT = Path(__file__).resolve().parents[1]
REPO_DATA = ROOT / "data"
PKG_DATA = ROOT / "rsm_lrg" / "data"


@pytest.mark.parametrize("path", sorted(p.name for p in REPO_DATA.iterdir() if p.is_file()))
def test_package_copy_is_identical(path):
    assert (PKG_DATA / path).read_bytes() == (REPO_DATA / path).read_bytes(), (
        f"rsm_lrg/data/{path} differs from data/{path}; copy data/ into rsm_lrg/data/"
    )


def test_table4_is_the_paper_table():
    # Source: the paper, Table 4 (27 runs; run 6 and 17 and 21 are the centre runs).
    df = datasets.load_table4()
    assert list(df.columns) == ["order", "thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2", "tcr_c_per_min"]
    assert len(df) == 27
    centre = df[(df.thickness_m == 0.0003) & (df.stroke_m == 0.05) & (df.velocity_m_s == 0.5) & (df.acceleration_m_s2 == 30)]
    assert sorted(centre.tcr_c_per_min) == [0.033, 0.034, 0.034]


def test_equation19_has_15_terms():
    eq = datasets.load_equation19()
    assert len(eq) == 15 and eq["Intercept"] == 0.03367
