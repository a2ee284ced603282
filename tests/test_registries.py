"""The registries of loss terms, operating modes and architectures (issue 22)."""

import numpy as np
import pytest

from ballcvt import InputError, Variator, load_builtin
from ballcvt.model.architectures import (
    CONTACT_NAMES,
    Architecture,
    SingleIdler,
    contact_layout,
)
from ballcvt.model.losses import DragInputs, LossTerm, drag_kinds, parasitic_torques
from ballcvt.model.modes import OperatingMode, resolve_mode
from ballcvt.params import ARCHITECTURES as PARAM_ARCHITECTURES
from ballcvt.registry import ARCHITECTURES, LOSS_TERMS, OPERATING_MODES

F = 2000.0


@pytest.fixture
def ball_drag_term():
    """A constant 1 mN m drag on every ball, registered for one test."""
    term = LOSS_TERMS.register(LossTerm("test_roller_drag", "rollers", lambda at: 1e-3))
    yield term
    LOSS_TERMS.unregister(term.name)


def test_builtin_loss_terms_in_order():
    assert LOSS_TERMS.names() == (
        "roller_churning", "disc_churning", "seals", "disc_bearing",
        "shell_bearings", "driver_bearing",  # the hub's own bearings (issue 27)
    )
    assert drag_kinds() == ("churning", "seals", "disc_bearings", "hub_bearings")
    for _, term in LOSS_TERMS.items():
        assert term.parameters.startswith("design.parasitic")


def test_loss_term_is_checked():
    with pytest.raises(InputError, match="acts_on"):
        LossTerm("x", "carrier", lambda at: 0.0)
    assert LossTerm("x", "input", lambda at: 0.0).kind == "x"
    with pytest.raises(InputError, match="not yet registered"):
        LOSS_TERMS.register(LossTerm("seals", "input", lambda at: 0.0))


def test_user_term_enters_the_balances_and_the_breakdown(ball_drag_term):
    design, fluid = load_builtin()
    ball, d0, d2 = parasitic_torques(design, fluid, 200.0, 100.0, 600.0, 1e4)
    assert ball == 1e-3 and d0.shape == (5,) and not d0.any() and not d2.any()
    r = Variator().solve(1.0, 20.0, clamp_force=F, input_speed_rpm=2000)
    ls = r.losses
    assert ls["test_roller_drag"] > 0 and ls["parasitic"] == ls["test_roller_drag"]
    # n balls, each braked by 1 mN m at its spin speed
    assert ls["test_roller_drag"] == pytest.approx(design.n_rollers * 1e-3 * abs(r.roller_speed),
                                                 rel=1e-12)
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-9)
    with pytest.raises(InputError, match="loss term"):
        Variator().solve(1.2, 10.0, clamp_force=F, input_speed=20.0,
                         mode="disc2_held_carrier_drives")


def test_user_term_between_the_discs_brakes_the_faster_disc():
    term = LOSS_TERMS.register(LossTerm("test_between", "between_discs",
                                        lambda at: 2.0 * np.abs(at.speed)))
    try:
        design, fluid = load_builtin()
        _, d0, d2 = parasitic_torques(design, fluid, 200.0, 150.0, 600.0, 1e4)
        assert d0[-1] == 100.0 and d2[-1] == -100.0
    finally:
        LOSS_TERMS.unregister(term.name)
    assert "test_between" not in drag_kinds()


def test_drag_inputs_carry_the_member_speed():
    seen = {}

    def record(at: DragInputs):
        seen.setdefault("speeds", []).append(float(at.speed))
        return 0.0

    LOSS_TERMS.register(LossTerm("test_record", "shafts", record))
    try:
        design, fluid = load_builtin()
        parasitic_torques(design, fluid, 200.0, 150.0, 600.0, 1e4)
    finally:
        LOSS_TERMS.unregister("test_record")
    assert seen["speeds"] == [200.0, 150.0]


def test_operating_modes_by_name():
    assert OPERATING_MODES.names()[0] == "carrier_held"
    assert len(OPERATING_MODES) == 6
    assert resolve_mode(None) == OperatingMode() == resolve_mode("carrier_held")
    assert resolve_mode("disc2_held_carrier_drives") == OperatingMode("disc2", "carrier")
    with pytest.raises(InputError, match="mode = 'nope'.*carrier_held"):
        resolve_mode("nope")
    v = Variator()
    a = v.solve(1.5, 15.0, clamp_force=F, input_speed=40.0, mode="disc2_held_carrier_drives")
    b = v.solve(1.5, 15.0, clamp_force=F, input_speed=40.0,
                mode=OperatingMode("disc2", "carrier"))
    assert a.eta == b.eta and a.speeds == b.speeds


def test_architectures_are_objects():
    for name in ("double", "single"):
        arch = ARCHITECTURES.get(name)
        assert isinstance(arch, Architecture) and arch.name == name
        assert CONTACT_NAMES[name] == arch.contacts
    assert list(PARAM_ARCHITECTURES) == list(ARCHITECTURES) == ["double", "single"]
    with pytest.raises(InputError, match="architecture = 'triple'.*double, single"):
        Variator(architecture="triple")


def test_a_registered_architecture_is_usable_everywhere():
    class Copy(SingleIdler):
        name = "single_copy"

    ARCHITECTURES.register(Copy())
    try:
        assert "single_copy" in PARAM_ARCHITECTURES and "single_copy" in CONTACT_NAMES
        design, _ = load_builtin()
        a, b = contact_layout(design, "single"), contact_layout(design, "single_copy")
        assert b.architecture == "single_copy" and np.array_equal(a.load_factor, b.load_factor)
        r = Variator(architecture="single_copy").solve(1.2, 20.0, clamp_force=F,
                                                        input_speed_rpm=1000)
        s = Variator(architecture="single").solve(1.2, 20.0, clamp_force=F,
                                                  input_speed_rpm=1000)
        assert r.eta == s.eta
    finally:
        ARCHITECTURES.unregister("single_copy")


def test_moved_feasibility_names_warn():
    import ballcvt.params.feasibility as feas
    from ballcvt.model.kinematics import tilt_limits
    from ballcvt.errors import BallCVTDeprecationWarning
    with pytest.warns(BallCVTDeprecationWarning, match="tilt_limits"):
        assert feas.tilt_limits is tilt_limits
