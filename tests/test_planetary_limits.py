"""Planetary modes have the default's limit, capacity and map (issue 23), batched; an
overload is a one-line TractionLimitError naming the contact and its creep."""

import json

import numpy as np
import pytest

from ballcvt import TractionLimitError, Variator
from ballcvt.api import MapGrid
from ballcvt.interfaces.cli.main import main
from ballcvt.model.modes import OperatingMode

F = 2000.0
CARRIER_DRIVES = OperatingMode("disc2", "carrier")
DISC0_HELD = OperatingMode("disc0", "carrier")


@pytest.fixture(scope="module")
def v():
    return Variator()


@pytest.mark.parametrize("mode, ratio", [(CARRIER_DRIVES, 1.3), (DISC0_HELD, 0.8),
                                         (OperatingMode("carrier", "disc2"), 1.2)],
                         ids=lambda x: getattr(x, "label", str(x)))
def test_limit_is_where_the_solve_stops_to_1e_3(v, mode, ratio):
    at = {"clamp_force": F, "input_speed_rpm": 600, "mode": mode}
    lim = v.limit_torque(ratio, **at)
    assert lim > 0
    zero = v.solve(ratio, 0.0, **at)
    sign = -1.0 if zero.speeds[mode.driven] < 0 else 1.0
    below = v.solve(ratio, sign * lim * (1 - 1e-3), **at)
    assert max(abs(c.creep) for c in below.relative.contacts.values()) <= v.design.creep_limit
    with pytest.raises(TractionLimitError) as err:
        v.solve(ratio, sign * lim * (1 + 2e-3), **at)
    assert err.value.limit_torque == pytest.approx(lim, rel=1e-12)


def test_overload_names_the_range_in_the_loads_direction(v):
    """A negative load's capacity is its own (``limit_load_batch`` searches the load's
    direction): the message names the range on the negative side, not ``0 <= T <= L``
    (session 31: it said ``allowed 0 <= output_torque <= 157.2 N m`` of -170 N m)."""
    at = {"clamp_force": F, "input_speed_rpm": 600, "mode": CARRIER_DRIVES}
    for sign in (-1.0, 1.0):
        with pytest.raises(TractionLimitError) as err:
            v.solve(1.3, sign * 170.0, **at)
        cap = err.value.limit_torque
        want = (f"allowed output_torque {-cap:.4g} to 0 N m" if sign < 0
                else f"allowed 0 <= output_torque <= {cap:.4g} N m")
        assert str(err.value).endswith(want)


@pytest.mark.parametrize("load", [200.0, 400.0])
def test_overload_is_one_line_naming_the_contact(v, load):
    with pytest.raises(TractionLimitError) as err:
        v.solve(0.8, load, clamp_force=F, input_speed_rpm=600, mode=DISC0_HELD)
    text = str(err.value)
    assert "\n" not in text and "bracket" not in text
    assert "output contact's creep" in text and "disc0 held" in text


def test_cli_overload_exit_code_and_message(capsys):
    assert main(["point", "--held", "disc0", "--driver", "carrier", "--ratio", "0.8",
                 "--torque", "200", "--speed", "600"]) == 2
    err = capsys.readouterr().err
    assert "exceeds the traction capacity" in err and "bracket" not in err


def test_map_in_a_mode(v):
    ds = v.efficiency_map(MapGrid((0.6, 1.6), 5, None, 6), input_speed_rpm=600,
                          clamp_force=F, mode=CARRIER_DRIVES)
    assert ds.eta.shape == (5, 6)
    eta = ds.eta.values[np.isfinite(ds.eta.values)]
    assert ((0 <= eta) & (eta <= 1)).all()
    st, t, lim = ds.status.values, ds.output_torque.values, ds.limit_torque.values
    assert (st[t[None, :] <= lim[:, None] * (1 - 2e-3)] == 0).all()
    assert (st[t[None, :] > lim[:, None] * (1 + 2e-3)] == 1).all()
    for i, ratio in enumerate(ds.ratio.values):
        one = v.limit_torque(float(ratio), clamp_force=F, input_speed_rpm=600,
                             mode=CARRIER_DRIVES)
        assert one == pytest.approx(lim[i], rel=2e-3)     # both bisected to 1e-3
    r = v.solve(1.1, float(t[1]), clamp_force=F, input_speed_rpm=600, mode=CARRIER_DRIVES)
    assert float(ds.eta.sel(ratio=1.1).isel(output_torque=1)) == pytest.approx(r.eta, abs=1e-9)


def test_cli_limit_and_map_take_the_mode(capsys, tmp_path):
    assert main(["limit", "--held", "disc2", "--driver", "carrier", "--ratio", "1.3",
                 "--speed", "600", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["mode"]["driven"] == "disc0"
    ref = Variator().limit_torque(1.3, clamp_force=F, input_speed_rpm=600,
                                  mode=CARRIER_DRIVES)
    assert data["limit_torque"] == pytest.approx(ref, rel=1e-12)
    out = tmp_path / "m"
    assert main(["map", "--held", "disc0", "--driver", "carrier", "--speed", "600",
                 "--n-ratio", "4", "--n-torque", "3", "--out", str(out), "--quiet"]) == 0
    assert {p.name for p in out.iterdir()} >= {"map.nc", "map.csv", "map.png"}


def test_cycle_in_a_mode(v, tmp_path):
    """A duty cycle with disc 2 held and the carrier driving at 600 rpm: every step that
    runs meets the driven speed after the creep correction, equals a point solve, and the
    energy adds up; overloads are flagged beyond the capacity; the CLI takes the mode."""
    from ballcvt.api import cycle_from_arrays
    from ballcvt.units import rpm_to_rad_s
    w = rpm_to_rad_s(np.array([0.0, 50.0, 120.0, 200.0, 200.0]))
    load = np.array([0.0, 20.0, 40.0, 60.0, 400.0])
    c = cycle_from_arrays(time=np.arange(5.0), output_speed=w, output_torque=load)
    res = v.run_cycle(c, clamp_force=F, target_input_speed_rpm=600, mode=CARRIER_DRIVES)
    st = res.steps
    assert st.flag.tolist() == ["idle", "ok", "ok", "ok", "beyond_capacity"]
    ok = st.flag == "ok"
    assert np.allclose(rpm_to_rad_s(st.disc0_speed_rpm[ok]), w[ok], rtol=1e-6)
    r = v.solve(float(st.ratio[2]), 40.0, clamp_force=F, input_speed_rpm=600,
                mode=CARRIER_DRIVES)
    assert st.eta[2] == pytest.approx(r.eta, abs=1e-9)
    assert st.input_power[2] == pytest.approx(r.input_power, rel=1e-9)
    s = res.summary
    dt = st.duration[ok]
    assert s["energy_in_J"] == pytest.approx(float((st.input_power[ok] * dt).sum()))
    assert 0 < s["efficiency"] < 1
    assert s["energy_in_J"] - s["energy_out_J"] == pytest.approx(s["losses_J"]["total"],
                                                                 rel=1e-8)
    path = tmp_path / "c.csv"
    path.write_text("time [s],output_speed [rpm],output_torque [N m]\n0,0,0\n1,50,20\n"
                    "2,120,40\n")
    assert main(["cycle", str(path), "--held", "disc2", "--driver", "carrier",
                 "--target-speed", "600", "--out", str(tmp_path / "o"), "--quiet"]) == 0
    assert (tmp_path / "o" / "steps.csv").exists()


def test_cycle_settings_in_a_mode_and_the_refused_laws(v):
    """issue 23: `CycleSettings(target_input_speed_rpm=...)` (strategy None: the target
    speed's) runs in a mode as it does in the default one; the cam and optimal laws are
    refused in one line that says what to use instead."""
    from ballcvt import CycleSettings, InputError
    from ballcvt.api import cycle_from_arrays
    from ballcvt.units import rpm_to_rad_s
    w = rpm_to_rad_s(np.array([50.0, 120.0]))
    c = cycle_from_arrays(time=[0.0, 1.0], output_speed=w, output_torque=[20.0, 40.0])
    how = CycleSettings(target_input_speed_rpm=600, progress=False)
    res = v.run_cycle(c, clamp_force=F, settings=how, mode=CARRIER_DRIVES)
    assert res.steps.flag.tolist() == ["ok", "ok"]
    for law in ("cam", "optimal"):
        with pytest.raises(InputError) as err:
            v.limit_torque(1.0, clamp_law=law, input_speed_rpm=600, mode=CARRIER_DRIVES)
        assert len(str(err.value).splitlines()) == 1 and "clamp_force instead" in str(err.value)
