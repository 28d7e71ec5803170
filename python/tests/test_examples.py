"""The examples of examples/python, run on a few points: what they plot must be the physics."""

import math
import os
import sys

import pytest

import rigidity

sys.path.insert(0, os.path.join(os.environ.get("RIGIDITY_SOURCE_DIR", "."), "examples", "python"))
import wall_impact  # noqa: E402


@pytest.mark.parametrize("V,v", [(1.0, 0.2), (1.0, 0.9), (0.5, 0.2), (0.9, 0.6), (0.3, 0.25)])
def test_wall_impact_runs_match_the_closed_forms(V, v):
    model, parameters = ("rigid", {}) if V == 1.0 else ("hooke", {"wave_speed": V})
    p, contact, rebound = wall_impact.impact(model, v, **parameters)
    p_exact, contact_exact, rebound_exact = wall_impact.closed_form(V, v)
    assert p == pytest.approx(p_exact, rel=1e-10)
    assert contact == pytest.approx(contact_exact, rel=1e-10)
    assert rebound == pytest.approx(rebound_exact, rel=1e-10)


def test_the_closed_form_is_the_papers_for_the_rigid_bar():
    # docs/materials.md: v = 0.6 -> s = 1/2, p = 3/2, contact 2 s = 1; hooke V = 0.5 at 0.2 -> p = 1/9.
    assert wall_impact.closed_form(1.0, 0.6) == pytest.approx((1.5, 1.0, -0.6), rel=1e-12)
    assert wall_impact.closed_form(0.5, 0.2)[0] == pytest.approx(1.0 / 9.0, rel=1e-9)


def test_a_hooke_bar_hit_at_its_wave_speed_is_refused():
    with pytest.raises(rigidity.InadmissibleError):
        wall_impact.impact("hooke", 0.55, wave_speed=0.5)


def test_the_fluid_rebounds_slower_than_it_came():
    _, _, rebound = wall_impact.impact("constant_sound_speed", 0.5, sound_speed=0.5)
    assert -0.5 < rebound < -0.3 and math.isfinite(rebound)


import work_precision  # noqa: E402


def test_the_exact_fan_joins_the_piston_state_to_the_gas_at_rest():
    s_piston = work_precision.S0 * math.exp(math.atanh(work_precision.U) / work_precision.V)
    assert work_precision.exact_stretch(0.0, work_precision.T) == pytest.approx(s_piston, rel=1e-12)
    assert work_precision.exact_stretch(1.0, work_precision.T) == work_precision.S0  # the head has not got there
    inside = work_precision.exact_stretch(0.35, work_precision.T)  # X/t = 0.7, between tail and head
    assert work_precision.S0 < inside < s_piston
    assert work_precision.label_speed(inside) == pytest.approx(0.35 / work_precision.T, rel=1e-9)


def test_front_tracking_is_the_exact_fan_at_any_tolerance():
    # Its steps stand for the centred fan until one of them interacts (none does here).
    coarse, _ = work_precision.error_and_time({"method": "characteristics", "tolerance": 1e-2})
    fine, _ = work_precision.error_and_time({"method": "characteristics", "tolerance": 1e-3})
    assert coarse < 1e-12
    assert fine < 1e-12
    few, _ = work_precision.error_and_time({"method": "finite_volume", "cells": 100, "order": 2})
    many, _ = work_precision.error_and_time({"method": "finite_volume", "cells": 400, "order": 2})
    assert many < few / 2
