"""Parameters: shipped TOML = dataclass defaults, overrides, validation."""

import dataclasses
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rsm_lrg.physics.params import (
    ASSUMPTIONS,
    PARAM_INFO,
    LRGParams,
    check_values,
    load_params,
    param_names,
    parse_assignments,
)

ROOT = Path(__file__).resolve().parents[2]


def test_toml_is_the_dataclass():
    raw = tomllib.loads((ROOT / "data" / "lrg_shs15v.toml").read_text())
    assert sorted(raw) == sorted(param_names())
    p = LRGParams()
    for name, entry in raw.items():
        assert getattr(p, name) == entry["value"], name
        assert entry["unit"] and entry["source"], name


def test_every_assumption_is_marked_and_explained():
    # The paper does not give these (brief / issue 3): each carries a rationale.
    for name in ("hinge_width_m", "hinge_length_m", "hinge_damping_ratio", "frame_mass_fraction",
                 "rail_length_m", "dwell_s"):
        assert name in ASSUMPTIONS and len(ASSUMPTIONS[name]) > 40
        assert PARAM_INFO[name]["source"] == "ASSUMPTION"


def test_paper_values():
    # Source: paper Sections 2.1-2.3, Table 1; THK SHS15V catalog.
    p = LRGParams()
    assert (p.preload_n, p.mu_s, p.mu_k, p.stage_mass_kg, p.hinge_count) == (171.0, 0.03, 0.02, 0.27, 4)
    assert (p.ball_radius_m, p.ball_rows, p.balls_per_row, p.contact_angle_deg) == (1.3497e-3, 4, 18, 45.0)
    assert (p.wear_coefficient, p.hardness_hb, p.char_length_m, p.air_velocity_m_s) == (4e-5, 523.0, 0.015, 0.3)
    assert (p.block_width_m, p.block_length_m, p.block_height_m) == (0.034, 0.0644, 0.024)
    assert (p.rail_width_m, p.rail_height_m, p.rail_mass_kg_per_m, p.carriage_mass_kg) == (0.015, 0.013, 1.3, 0.19)
    assert p.normal_load_n == pytest.approx(173.65, abs=0.005)  # paper: 173.65 N
    assert p.f_mu_max_n == pytest.approx(5.209, abs=0.0005)    # paper: 5.209 N


def test_overrides_three_ways(tmp_path):
    p = LRGParams().with_overrides(mu_k=0.01, hinge_count=2)
    assert p.mu_k == 0.01 and p.hinge_count == 2 and isinstance(p.hinge_count, int)
    assert dataclasses.replace(LRGParams(), stroke_m=0.04).stroke_m == 0.04
    f = tmp_path / "o.toml"
    f.write_text('mu_k = 0.015\n[stroke_m]\nvalue = 0.06\nunit = "m"\n')
    q = load_params(f, velocity_m_s=0.4)
    assert (q.mu_k, q.stroke_m, q.velocity_m_s) == (0.015, 0.06, 0.4)
    assert parse_assignments(["hinge_thickness_m=1e-4"]) == {"hinge_thickness_m": 1e-4}


@pytest.mark.parametrize("name,value,words", [
    ("stroke_m", 0.0, "stroke_m must be > 0"),
    ("stage_mass_kg", -1.0, "stage_mass_kg must be > 0"),
    ("velocity_m_s", -0.5, "velocity_m_s must be > 0"),
    ("hinge_thickness_m", 0.0, "hinge_thickness_m"),
    ("mu_s", 1.2, "mu_s must lie in [0, 1]"),
    ("mu_k", -0.1, "mu_k must lie in [0, 1]"),
    ("frame_mass_fraction", 1.0, "frame_mass_fraction"),
    ("hinge_count", 2.5, "hinge_count must be a whole number"),
    ("dwell_s", -1.0, "dwell_s must be >= 0"),
    ("contact_angle_deg", 90.0, "contact_angle_deg"),
    ("ambient_c", -300.0, "ambient_c"),
    ("stroke_m", float("nan"), "stroke_m must be finite"),
    ("stroke_m", "abc", "stroke_m must be a number"),
])
def test_bad_values_name_the_parameter(name, value, words):
    with pytest.raises(ValueError, match=words.replace("[", r"\[").replace("]", r"\]")):
        LRGParams().with_overrides(**{name: value})


def test_unknown_name_and_bad_file(tmp_path):
    with pytest.raises(ValueError, match="unknown parameter 'mu_kk'.*mu_k"):
        LRGParams().with_overrides(mu_kk=0.1)
    with pytest.raises(ValueError, match="NAME=VALUE"):
        parse_assignments(["mu_k"])
    bad = tmp_path / "b.toml"
    bad.write_text("mu_k = 3\n")
    with pytest.raises(ValueError, match=r"b\.toml: parameter mu_k"):
        load_params(bad)
    broken = tmp_path / "c.toml"
    broken.write_text("mu_k = = 3\n")
    with pytest.raises(ValueError, match="not valid TOML"):
        load_params(broken)


def test_check_values_on_columns():
    check_values("hinge_thickness_m", np.array([1e-4, 3e-4]))
    with pytest.raises(ValueError, match=r"row 2"):
        check_values("mu_k", np.array([0.01, 0.02, 1.5]))


def test_a_name_given_twice_is_refused():
    # the later value used to win silently (rsm-lrg physics/simulate --param mu_k=.. --param mu_k=..)
    with pytest.raises(ValueError, match="mu_k is given more than once"):
        parse_assignments(["mu_k=0.05", " mu_k = 0.01"])
    assert parse_assignments(["mu_k=0.05", "mu_s=0.1"]) == {"mu_k": 0.05, "mu_s": 0.1}
