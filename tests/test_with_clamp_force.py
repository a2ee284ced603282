"""`with_clamp_force` (session 25): a problem at other clamping forces builds only the
fields that depend on the force, and gives exactly the problem `build_problem` gives."""

from dataclasses import fields

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import (
    CarrierFrame,
    OperatingInputs,
    build_problem,
    make_problem,
    with_clamp_force,
)
from ballcvt.errors import InputError
from ballcvt.params.drive import Drive
from ballcvt.solvers.clamped import with_clamp


def _same(a, b):
    """Every field of two problems equal, bit for bit."""
    for f in fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, np.ndarray):
            assert x.shape == np.shape(y), f.name
            assert np.array_equal(x, y), f.name
        else:
            assert x == y, f.name


def _variators():
    hub_design, hub_fluid = load_builtin("hub")  # its parasitic drags depend on the force
    return [Variator(), Variator(hub_design, hub_fluid)]


@pytest.mark.parametrize("which", [0, 1])
def test_the_same_problem_as_built_anew(which):
    v = _variators()[which]
    ratio, torque = np.linspace(0.6, 1.5, 4), np.array([0.0, 10.0, 40.0, 60.0])
    p = build_problem(v.design, v.fluid, v.architecture, ratio, torque, 2000.0, 209.4)
    forces = np.array([500.0, 900.0, 1500.0, 3000.0])
    got = with_clamp_force(p, forces)
    _same(got, build_problem(v.design, v.fluid, v.architecture, ratio, torque, forces, 209.4))
    if which:  # the drive whose drags grow with the clamping force
        assert np.any(got.disc_drag != p.disc_drag)
    _same(with_clamp(p, forces), got)  # the solvers' name for it


def test_a_single_point_and_a_force_of_another_shape():
    v = Variator()
    one = build_problem(v.design, v.fluid, v.architecture, 1.0, 40.0, 2000.0, 209.4)
    _same(with_clamp_force(one, 800.0),
          build_problem(v.design, v.fluid, v.architecture, 1.0, 40.0, 800.0, 209.4))
    # a force that broadcasts the batch up is built whole, as before
    wide = with_clamp_force(one, np.array([700.0, 800.0]))
    _same(wide, build_problem(v.design, v.fluid, v.architecture, 1.0, 40.0,
                              np.array([700.0, 800.0]), 209.4))


def test_another_frame_is_built_whole_in_the_paper_frame():
    v = Variator()
    drive = Drive(v.design, v.fluid, v.architecture)
    turning = make_problem(drive, OperatingInputs(1.0, 20.0, 2000.0, 209.4),
                           CarrierFrame(carrier_speed=120.0))
    got = with_clamp_force(turning, 1500.0)
    _same(got, build_problem(v.design, v.fluid, v.architecture, 1.0, 20.0, 1500.0, 209.4))


@pytest.mark.parametrize("force", [0.0, -5.0, np.nan])
def test_a_force_out_of_range_is_refused_by_name(force):
    v = Variator()
    p = build_problem(v.design, v.fluid, v.architecture, 1.0, 40.0, 2000.0, 209.4)
    with pytest.raises(InputError, match="clamp_force"):
        with_clamp_force(p, force)


def test_a_force_beyond_the_roelands_limit_is_refused():
    v = Variator()
    p = build_problem(v.design, v.fluid, v.architecture, 1.0, 40.0, 2000.0, 209.4)
    with pytest.raises(InputError, match="Roelands"):
        with_clamp_force(p, 1e9)
