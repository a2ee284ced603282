"""The moment about a ball's skew axis and the steady moments on results (docs/model.md §17).

Sign convention: ``skew_moment`` is the contacts' moment on the ball about the outward
radial axis ``+k`` (the skew axis), equal to the moment the carrier applies about the
direction of increasing skew ``-k``; the traction ``F_c`` is along ``+i`` and the spin
moment ``T_c`` about the outward ball normal ``z_c`` (docs/model.md §5).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from ballcvt import OperatingResult, Variator
from ballcvt.interfaces.cli.main import main
from ballcvt.model.architectures import contact_layout
from ballcvt.model.shift import skew_axis_moment

POINT = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}
EI, EJ, EK = np.eye(3)


@pytest.fixture(scope="module")
def paper():
    return Variator()


def _vector_moment(r, lay, rs):
    """The contacts' moment on the ball as a 3-vector, from ``r x F`` and the spin moments."""
    total = np.zeros(3)
    for n, c in enumerate(r.contacts.values()):
        z = lay.z_j[n] * EJ + lay.z_k[n] * EK
        total += np.cross(rs * z, c.tangential_force * EI) + c.spin_moment * z
    return total


def test_hand_check_one_contact():
    """Input disc at theta = 45 deg, r_S = 30 mm, F = 50 N along +i, T = 0.08 N m about z:
    lever r_S sin(theta) = 21.2 mm, so 1.0607 N m from the traction and
    cos(theta) 0.08 = 0.0566 N m from the spin moment, 1.1172 N m about +k."""
    th, rs, f, t = math.radians(45.0), 0.03, 50.0, 0.08
    zj, zk = -math.sin(th), math.cos(th)
    got = skew_axis_moment(np.array([f]), np.array([t]), np.array([zj]), np.array([zk]), rs)
    assert got == pytest.approx(1.1172, abs=1e-4)
    z = zj * EJ + zk * EK
    assert got == pytest.approx((np.cross(rs * z, f * EI) + t * z) @ EK, rel=1e-14)


def test_lateral_forces_have_no_skew_part():
    """A transverse force ``F_y kappa (i x z_c)`` at ``r_S z_c`` turns the ball about
    ``i`` only: no moment about the skew axis (which is why `skew_axis_moment` has none)."""
    v = Variator()
    for arch in ("double", "single"):
        lay = contact_layout(v.design, arch)
        for n in range(lay.z_j.size):
            z = lay.z_j[n] * EJ + lay.z_k[n] * EK
            m = np.cross(0.03 * z, 7.0 * lay.kappa[n] * np.cross(EI, z))
            assert m @ EK == pytest.approx(0.0, abs=1e-15)
            assert m @ EI == pytest.approx(lay.kappa[n] * 0.03 * 7.0, rel=1e-12)


def test_double_idler_ratio_one_symmetry(paper):
    """Table EI at ratio 1 (theta_0 = theta_2 = 45 deg, gamma = 0): the two idler contacts
    are mirror images across the ball's equator (z_j = -/+ sin alpha, equal z_k), with equal
    tractions and opposite spin moments, so their contributions cancel; the discs'
    tractions (input along +i at z_j < 0, output along -i at z_j > 0) add into a couple
    r_S sin(45 deg) (F_0 - F_2) > 0, while their spin moments (opposite spins, equal z_k)
    nearly cancel (the output's traction is smaller by the losses)."""
    r = paper.solve(1.0, 40.0, **POINT)
    rs, s45 = paper.design.roller_radius, math.sin(math.radians(45.0))
    lay = contact_layout(paper.design, "double")
    c = r.contacts
    part = {
        n: skew_axis_moment(
            np.array([x.tangential_force]),
            np.array([x.spin_moment]),
            lay.z_j[i : i + 1],
            lay.z_k[i : i + 1],
            rs,
        )
        for i, (n, x) in enumerate(c.items())
    }
    assert part["idler_a"] + part["idler_b"] == pytest.approx(0.0, abs=1e-12)
    couple = rs * s45 * (c["input"].tangential_force - c["output"].tangential_force)
    spin = s45 * (c["input"].spin_moment + c["output"].spin_moment)
    assert r.skew_moment == pytest.approx(couple + spin, rel=1e-12)
    assert couple > 0.0 and abs(spin) < 0.005 * couple
    # exactly equal and opposite disc contacts: the spin parts cancel, the tractions add
    f0, t0 = 50.0, 0.08
    both = skew_axis_moment(
        np.array([f0, -f0]), np.array([t0, -t0]), lay.z_j[[0, -1]], lay.z_k[[0, -1]], rs
    )
    assert both == pytest.approx(2.0 * rs * s45 * f0, rel=1e-14)


@pytest.mark.parametrize("arch", ["double", "single"])
@pytest.mark.parametrize("ratio", [0.5, 1.76])
def test_closes_the_ball_moment_balance(arch, ratio):
    """``skew_moment`` is the k part of the contacts' moment (3-D ``r x F`` sum); its u
    part is the axle-end couple ``r_S (F_Ra - F_Rb) / 2`` the solver balanced."""
    v = Variator(architecture=arch)
    r = v.solve(ratio, 40.0, **POINT)
    rs, lay = v.design.roller_radius, contact_layout(v.design, arch)
    m = _vector_moment(r, lay, rs)
    assert r.skew_moment == pytest.approx(m @ EK, rel=1e-10)
    u = math.sin(r.tilt) * EJ + math.cos(r.tilt) * EK
    f_a, f_b = r.axle_reactions
    assert m @ u == pytest.approx(rs * (f_a - f_b) / 2.0, rel=1e-9)
    assert r.skew_moment > 0.0  # the discs' traction couple dominates (see above)


def test_shift_moments_and_map_agree_with_the_result(paper):
    """At rate 0 the lateral path's skew moment is the result's; a tilt changes it only
    through the contacts' mu and chi (the side slip takes part of the traction)."""
    r = paper.solve(1.76, 40.0, **POINT)
    still = paper.shift_moments_at(r)
    assert still.skew_moment == pytest.approx(r.skew_moment, rel=1e-6)
    assert still.holding_moment == r.holding_moment
    moving = paper.shift_moments_at(r, tilt_rate=math.radians(30.0))
    assert moving.skew_moment == pytest.approx(r.skew_moment, rel=0.05)
    from ballcvt import MapGrid

    ds = paper.efficiency_map(MapGrid((0.8, 1.6), 2, 60.0, 2), **POINT)
    out = paper.map_shift_effort(ds)
    ratio, torque = float(ds.ratio[0]), float(ds.output_torque[0])
    point = paper.shift_moments(ratio, torque, **POINT)
    got = float(out.skew_moment.sel(ratio=ratio, output_torque=torque).squeeze())
    assert got == pytest.approx(point.skew_moment, rel=1e-9)
    assert out.skew_moment.attrs["units"] == "N m"


def test_result_round_trip_and_old_files(paper, tmp_path):
    r = paper.solve(1.2, 30.0, **POINT)
    assert math.isfinite(r.holding_moment) and math.isfinite(r.skew_moment)
    path = tmp_path / "r.json"
    r.save(path)
    back = OperatingResult.load(path)
    assert back == r
    data = r.to_dict()
    assert data["skew_moment_Nm"] == data["skew_moment"] == r.skew_moment
    for key in ("holding_moment", "skew_moment", "skew_moment_Nm"):
        data.pop(key)
    old = OperatingResult.from_dict(data)
    assert math.isnan(old.holding_moment) and math.isnan(old.skew_moment)


def test_point_json(capsys):
    assert main(["point", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert abs(data["holding_moment"]) < 1e-12
    assert data["skew_moment_Nm"] == pytest.approx(2.2096, rel=1e-3)


def test_a_law_without_a_side_slip_form_still_solves():
    """A registered law without ``lateral``: the point solves, its holding moment is NaN
    (unknown) and its skew moment (from the solved forces) is the isothermal law's."""
    import dataclasses

    from ballcvt.registry import TRACTION_LAWS

    law = dataclasses.replace(TRACTION_LAWS.get("isothermal"), name="no_side_slip", lateral=None)
    TRACTION_LAWS.register(law)
    try:
        v = Variator()
        plain = v.solve(1.0, 40.0, **POINT)
        r = Variator(fluid=v.fluid.with_traction_law("no_side_slip")).solve(1.0, 40.0, **POINT)
    finally:
        TRACTION_LAWS.unregister("no_side_slip")
    assert math.isnan(r.holding_moment)
    assert r.skew_moment == pytest.approx(plain.skew_moment, rel=1e-12)
