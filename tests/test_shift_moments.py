"""Holding and tilt-direct shift moments (docs/model.md §17): `Variator.shift_moments`."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import ballcvt
from ballcvt import ShiftMoments, Variator
from ballcvt.interfaces.cli.main import main
from ballcvt.model.shift import TiltContacts, tilt_moments
from ballcvt.model.traction import ContactState, limiting_traction

#: The paper's point: ratio 1, 40 N m, F_N0 2 kN, 2000 rpm.
POINT = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


@pytest.fixture(scope="module")
def paper():
    return Variator()


def _moment(v, rate_deg, ratio=1.0, torque=40.0, **point):
    kw = {**POINT, **point}
    return v.shift_moments(ratio, torque, tilt_rate=math.radians(rate_deg), **kw)


def test_public_names(paper):
    assert ballcvt.ShiftMoments is ballcvt.api.ShiftMoments is ShiftMoments
    got = _moment(paper, 30.0)
    assert isinstance(got, ShiftMoments)
    assert got.contacts == ("input", "idler_a", "idler_b", "output")
    assert len(got.side_slip) == len(got.lateral_force) == 4
    assert got.shifter_moment == pytest.approx(8 * (got.holding_moment + got.shift_moment))
    assert got.tilt_rate == pytest.approx(math.radians(30.0))


def test_zero_tilt_rate(paper):
    """No tilt, no shift moment; the rigid-plastic law's contacts hold the tilt for free."""
    got = paper.shift_moments(1.0, 40.0, **POINT)
    assert got.shift_moment == 0.0 and got.side_slip == (0.0,) * 4
    assert abs(got.holding_moment) < 1e-12 and not got.saturated


@pytest.mark.parametrize("law", ["isothermal", "thermal", "viscoelastic"])
def test_odd_lateral_laws_have_no_lateral_force_without_side_slip(law):
    """A law that declares ``odd_lateral`` (its ``mu_y`` odd in the side slip) gives
    ``mu_y`` = 0 at zero side slip by its quadrature too, at every contact of a spinning,
    loaded point; `solve` then stores a holding moment of exactly zero without integrating
    it, and `lateral_coefficients` gives exactly zero. The Maxwell film does not declare
    it, and its holding moment is not zero."""
    from ballcvt.equilibrium.problem import build_problem
    from ballcvt.model.traction.base import TRACTION_LAWS, lateral_coefficients
    from ballcvt.results.moments import tilt_contacts
    from ballcvt.solvers.newton import solve_batch

    v = Variator(traction_law=law)
    got = v.solve(0.7, 40.0, **POINT)
    declared = TRACTION_LAWS.get(law).odd_lateral
    assert declared == (law != "viscoelastic")
    pb = build_problem(v.design, v.fluid, v.architecture, np.array([0.7]), 40.0, 2000.0,
                       2000.0 * math.pi / 30)
    st = solve_batch(pb, v.options).state
    c = tilt_contacts(pb, st, v.options.quadrature)
    raw = TRACTION_LAWS.get(law).lateral  # the law's quadrature, as registered
    mu, mu_y, _ = raw(c.state, v.fluid, 0.0, c.quadrature, c.entry)
    if declared:
        assert np.all(np.abs(mu_y) <= 1e-12 * np.max(np.abs(mu)))
        assert np.all(lateral_coefficients(c.state, v.fluid, 0.0, c.quadrature)[1] == 0.0)
        assert got.holding_moment == 0.0
    else:
        assert np.any(np.abs(mu_y) > 1e-12 * np.max(np.abs(mu)))
        assert got.holding_moment != 0.0


def test_viscoelastic_holding_moment_is_small_and_finite():
    """The Maxwell film's entry memory gives a spinning contact a small lateral force."""
    v = Variator(traction_law="viscoelastic")
    got = _moment(v, 30.0)
    assert 0.0 < abs(got.holding_moment) < 1e-3 * abs(got.shift_moment)


def test_sign_resists_the_tilt(paper):
    """The shifter does positive work: the moment has the sign of the rate (and is odd)."""
    up, down = _moment(paper, 5.0), _moment(paper, -5.0)
    assert up.shift_moment > 0.0
    assert down.shift_moment == pytest.approx(-up.shift_moment, rel=1e-6)


def test_linear_in_rate_and_inverse_in_speed(paper):
    """Linear range: proportional to the rate, inversely proportional to the input speed."""
    m1, m2 = _moment(paper, 0.1).shift_moment, _moment(paper, 0.2).shift_moment
    assert m2 / m1 == pytest.approx(2.0, rel=1e-3)
    slow = _moment(paper, 0.1, input_speed_rpm=1000.0).shift_moment
    fast = _moment(paper, 0.1, input_speed_rpm=4000.0).shift_moment
    assert slow / m1 == pytest.approx(2.0, rel=0.03)
    assert fast / m1 == pytest.approx(0.5, rel=0.03)


def test_grows_with_load_as_two_thirds_power(paper):
    """Linear range at a fixed torque: the moment grows with the clamping force as about
    ``F_N^(2/3)`` (the spin's sliding field at its limiting shear stress, §17), not in
    proportion."""
    m = [_moment(paper, 0.1, clamp_force=f).shift_moment for f in (1000.0, 2000.0, 4000.0)]
    exponents = np.diff(np.log(m)) / np.log(2.0)
    assert np.all((exponents > 0.6) & (exponents < 0.75))


def test_saturates_at_the_traction_limit(paper):
    """At large rates the moment stops growing, bounded by the limiting shear stress."""
    slow, fast, faster = (_moment(paper, r) for r in (30.0, 2000.0, 6000.0))
    assert not slow.saturated and fast.saturated and faster.saturated
    assert faster.shift_moment / fast.shift_moment < 1.25
    r = paper.solve(1.0, 40.0, **POINT)
    bound = sum(
        c.normal_load
        * limiting_traction(
            ContactState(0, 0, c.semi_axis_x, c.semi_axis_y, c.p_max, c.normal_load, 1, 1, 1),
            paper.fluid,
        )
        for c in r.contacts.values()
    )
    assert faster.shift_moment < paper.design.roller_radius * bound


def test_hand_calculation_one_contact(paper):
    """One contact, no spin, no creep, constant viscosity, a slow tilt (Newtonian limit):
    the lateral force is ``F_y = (eta / h) pi a_x a_y V`` with the slip speed
    ``V = gamma_dot r_S``, and the moment about the tilt axis is ``r_S F_y``."""
    fluid = paper.fluid.model_copy(update={"pole_viscosity": paper.fluid.viscosity})
    ax, ay, h, u, fn, rs, rate = 2.1e-4, 7.0e-4, 1.2e-7, 4.0, 1800.0, 0.03, 1e-6
    pm = 1.5 * fn / (math.pi * ax * ay)
    state = ContactState(
        *(np.array([[v]]) for v in (0.0, 0.0, ax, ay, pm, fn, 0.045, u, h))
    )
    got = tilt_moments(TiltContacts(state, np.array([1.0]), rs, fluid), rate)
    slip_speed = rate * rs  # [m/s]
    f_y = fluid.viscosity / h * math.pi * ax * ay * slip_speed  # 2.9e-3 N by hand
    assert got.side_slip[0, 0] == pytest.approx(slip_speed / u)
    assert got.shift[0] == pytest.approx(rs * f_y, rel=1e-6)
    assert not got.saturated[0]


def test_map_shift_effort(paper):
    from ballcvt import MapGrid

    ds = paper.efficiency_map(
        MapGrid((0.8, 1.6), 2, 60.0, 2), input_speed_rpm=2000.0, clamp_force=2000.0
    )
    out = paper.map_shift_effort(ds, tilt_rate=math.radians(30.0))
    assert out.shift_moment.dims == ds.status.dims
    one = out.shift_moment.values[ds.status.values == 0]
    assert one.size and np.all(one > 0.0)
    r, t = float(ds.ratio[0]), float(ds.output_torque[0])
    point = _moment(paper, 30.0, ratio=r, torque=t)
    got = float(out.shift_moment.sel(ratio=r, output_torque=t).squeeze())
    assert got == pytest.approx(point.shift_moment, rel=1e-9)
    assert out.attrs["tilt_rate"] == pytest.approx(math.radians(30.0))


def _cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 0, err
    return out


def test_point_json_and_tilt_rate(capsys):
    data = json.loads(_cli(capsys, "point", "--json"))
    assert abs(data["holding_moment"]) < 1e-12 and "shift_moment_Nm" not in data
    data = json.loads(_cli(capsys, "point", "--json", "--tilt-rate", "30"))
    assert data["shift_moment_Nm"] == pytest.approx(1.4611, rel=1e-3)
    assert data["tilt_rate_deg_s"] == 30.0
    assert "N m per ball" in _cli(capsys, "point", "--tilt-rate", "30")


def test_map_cli_shift_effort(capsys, tmp_path):
    out = _cli(capsys, "map", "--out", str(tmp_path), "--n-ratio", "2", "--n-torque", "2",
               "--clamp", "2000", "--speed", "2000", "--shift-effort", "--tilt-rate", "30")
    assert "shift effort at 30 deg/s" in out
    assert (tmp_path / "shift_effort.png").exists()
    header = (tmp_path / "map.csv").read_text().splitlines()[0]
    assert "shift_moment [N m]" in header and "holding_moment [N m]" in header


@pytest.mark.parametrize("arch", ["double", "single"])
def test_contact_frame_from_rigid_body_kinematics(arch):
    """The body's velocity over the ball, from the rigid motions of the bodies and of a
    ball tilting at gamma_dot, is Eq. 55's field in the frame e_x = kappa i, e_z = -z_c,
    e_y = kappa (i x z_c): its x part the creep term, its y part the side slip of
    `tilt_side_slip`, its gradient the spin; the surfaces roll along ``entry`` e_x."""
    from ballcvt.analysis.shift_effort import solved_tilt_contacts
    from ballcvt.model.architectures import contact_layout
    from ballcvt.model.kinematics import creep_term
    from ballcvt.model.shift import tilt_side_slip
    from ballcvt.model.traction import Quadrature
    from ballcvt.params.drive import Drive

    v = Variator(architecture=arch)
    r = v.solve(1.3, 40.0, **POINT)
    lay, rs = contact_layout(v.design, arch), v.design.roller_radius
    i, j, k = np.eye(3)
    centre = rs * (1.0 + v.design.aspect_ratio) * k
    rate = 0.7  # [rad/s]
    spin_axis = np.cos(r.tilt) * j - np.sin(r.tilt) * k
    ball = r.roller_speed * spin_axis - rate * i  # tilting by +d gamma turns about -i
    names = list(r.contacts)
    creep = np.array([[r.contacts[n].creep for n in names]])
    inputs = [np.array([x]) for x in (r.ratio, r.output_torque, r.clamp_force, r.input_speed)]
    tc = solved_tilt_contacts(Drive(v.design, v.fluid, arch), inputs, creep, Quadrature())
    u_ref = np.asarray(tc.state.u_ref)
    slips = tilt_side_slip(rate, rs, u_ref, lay.kappa)[0]
    for n, name in enumerate(names):
        z = lay.z_j[n] * j + lay.z_k[n] * k
        ex, ez = lay.kappa[n] * i, -z
        ey = np.cross(ez, ex)
        assert np.allclose(ey, lay.kappa[n] * np.cross(i, z))
        omega = r.contacts[name].body_speed
        point = centre + rs * z

        def rel(q, omega=omega):  # the body's velocity over the ball's at q
            return omega * np.cross(j, q) - np.cross(ball, q - centre)

        u, d = abs(omega) * (point @ k), 1e-6
        here = rel(point)
        assert here @ ex / u == pytest.approx(creep_term(creep)[0, n], rel=1e-9, abs=1e-14)
        assert here @ ey / u == pytest.approx(slips[n], rel=1e-9)
        sigma_over_r = r.contacts[name].spin / (point @ k)
        assert (rel(point + d * ey) - here) @ ex / (u * d) == pytest.approx(-sigma_over_r, 1e-6)
        assert (rel(point + d * ex) - here) @ ey / (u * d) == pytest.approx(sigma_over_r, 1e-6)
        rolling = np.cross(r.roller_speed * spin_axis, rs * z) @ ex
        assert np.sign(rolling) == tc.entry[0, n]
        assert u == pytest.approx(u_ref[0, n], rel=1e-12)
