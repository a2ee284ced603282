"""Every loss is dissipated power, >= 0 (issue 23): each registered loss term's torque, and
every loss of a solved point, including within the creep band around tau_ID = 1 where the
discs' actual relative speed can have the other sign than the creep-free one."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballcvt import TractionLimitError, Variator, load_builtin
from ballcvt.errors import NoEquilibriumError
from ballcvt.model.losses import DragInputs, parasitic_drags
from ballcvt.registry import LOSS_TERMS
from drives import fixed_oil_hub

HUB = fixed_oil_hub()


@settings(max_examples=40, deadline=None)
@given(speed=st.floats(-2000.0, 2000.0), thrust=st.floats(-5e4, 5e4),
       name=st.sampled_from([name for name, _ in LOSS_TERMS.items()]))
def test_every_loss_term_is_a_magnitude(speed, thrust, name):
    term = LOSS_TERMS.get(name)
    design, fluid = HUB
    if not term.applies(design):
        return
    got = np.asarray(term.torque(DragInputs(design, fluid, np.asarray(speed), np.asarray(thrust))))
    assert np.all(got >= 0.0)


@settings(max_examples=30, deadline=None)
@given(w0=st.floats(1.0, 400.0), w2=st.floats(-400.0, 400.0), ws=st.floats(-900.0, 900.0),
       thrust=st.floats(0.0, 3e4))
def test_drag_power_is_dissipated(w0, w2, ws, thrust):
    """At any speeds, the drags times the speeds they oppose dissipate power."""
    design, fluid = HUB
    d = parasitic_drags(design, fluid, w0, w2, ws, thrust)
    assert np.all(d.roller >= 0.0)
    assert np.all(d.input * w0 + d.output * w2 >= -1e-12)


@settings(max_examples=30, deadline=None)
@given(ratio=st.one_of(st.floats(0.5, 2.0), st.floats(1.0, 1.04)),
       torque=st.floats(0.0, 60.0), rpm=st.floats(50.0, 4000.0))
def test_every_loss_of_a_point_is_non_negative(ratio, torque, rpm):
    """Everywhere, the creep band just above tau_ID = 1 drawn on its own as well."""
    v = Variator(*HUB)
    try:
        r = v.solve(ratio, torque, clamp_force=3000.0, input_speed_rpm=rpm)
    except (TractionLimitError, NoEquilibriumError):
        return
    assert all(value >= 0.0 for value in r.losses.values()), r.losses


@pytest.mark.parametrize("ratio, torque", [(1.001, 20.0), (1.003, 20.0), (1.005, 60.0)])
def test_disc_bearing_in_the_creep_band(ratio, torque):
    """The reproducer of issue 23: -0.44 W at tau_ID 1.001, 20 N m (-2.3 W with more torque),
    where the actual ratio is below 1 though the creep-free one is above."""
    v = Variator(*HUB)
    r = v.solve(ratio, torque, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.actual_ratio < 1.0 < ratio
    assert r.losses["disc_bearings"] >= 0.0
