"""A real hub's own losses and the models a drive names (issue 27, items 3 and 4):
the hub's bearings (Palmgren), the cam's ramp hysteresis, the hub's seals, and the
``[models]`` table with its precedence (call > drive file > package)."""

import json
import math

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.api import builtin_text, drive_to_toml, effective_models, open_drive
from ballcvt.errors import InputError
from ballcvt.interfaces.cli.main import main
from ballcvt.model.clamping import CamClamp
from ballcvt.model.losses import drag_power, palmgren_torque, parasitic_torques, seal_torque
from ballcvt.model.losses.base import drag_magnitudes
from ballcvt.params import parse_drive
from ballcvt.registry import LOSS_TERMS, LUBRICATION_MODELS, ModelChoice
from ballcvt.units import rpm_to_rad_s

W0 = rpm_to_rad_s(114.0)


@pytest.fixture(scope="module")
def hub():
    return load_builtin("hub")


def edited(old: str, new: str) -> str:
    text = builtin_text("hub")
    assert old in text
    return text.replace(old, new, 1)


# --- the hub's bearings -------------------------------------------------------------


def test_palmgren_by_hand():
    # 61805 shell bearing at 114 rpm under 300 N, grease base oil 110 mm^2/s
    m = palmgren_torque(W0, 300.0, 0.031, 110e-6, 1.5, 0.00025)
    m0 = 1e-7 * 1.5 * (110.0 * 114.0) ** (2.0 / 3.0) * 31.0**3  # [N mm]
    m1 = 0.00025 * 300.0 * 31.0  # [N mm]
    assert float(m) == pytest.approx(1e-3 * (m0 + m1), rel=1e-12)
    assert float(m) == pytest.approx(4.73e-3, rel=1e-2)  # [N m]


def test_palmgren_limits_and_units():
    # no load: the viscous part only; below nu n = 2000 Palmgren's floor 160
    assert float(palmgren_torque(W0, 0.0, 0.031, 110e-6, 1.5, 0.0)) == pytest.approx(
        1e-10 * 1.5 * (110.0 * 114.0) ** (2 / 3) * 31.0**3
    )
    assert float(palmgren_torque(0.0, 0.0, 0.031, 110e-6, 1.5, 0.00025)) == pytest.approx(
        1e-10 * 1.5 * 160.0 * 31.0**3
    )
    # the load part is linear in the load and the diameter; signs are ignored
    a = palmgren_torque(W0, 100.0, 0.02, 110e-6, 0.0, 0.001)
    assert float(a) == pytest.approx(1e-3 * 0.001 * 100.0 * 20.0)
    assert float(palmgren_torque(-W0, -100.0, 0.02, 110e-6, 0.0, 0.001)) == float(a)


def test_hub_bearing_terms_at_zero_speed_dissipate_nothing(hub):
    design, fluid = hub
    mag = drag_magnitudes(design, fluid, 0.0, 0.0, 0.0, 1e3, 10.0)
    assert np.all(drag_power(mag, 0.0, 0.0) == 0.0)
    col = mag.kinds.index("hub_bearings")
    assert mag.output[col] > 0.0  # the magnitude keeps its floor; the direction is zero


def test_chain_pull_follows_the_torque(hub):
    design, fluid = hub
    par = design.parasitic
    col = drag_magnitudes(design, fluid, W0, W0, 0.0, 1e3).kinds.index("hub_bearings")
    for t2 in (0.0, 8.0, 16.0):
        mag = drag_magnitudes(design, fluid, W0, 0.5 * W0, 0.0, 1e3, t2)
        pull = 0.5 * t2 / par.sprocket_radius  # lossless T_0 = T_2 omega_2 / omega_0
        expected = palmgren_torque(
            W0, pull, par.driver_bearing_diameter, par.hub_bearing_viscosity,
            par.hub_bearing_f0, par.hub_bearing_f1,
        )
        assert mag.input[col] == pytest.approx(float(expected), rel=1e-12)
        shell = 2 * palmgren_torque(
            0.5 * W0, 0.5 * par.wheel_load, par.hub_bearing_diameter,
            par.hub_bearing_viscosity, par.hub_bearing_f0, par.hub_bearing_f1,
        )
        assert mag.output[col] == pytest.approx(float(shell), rel=1e-12)


def test_hub_bearing_power_in_a_solved_point(hub):
    v = Variator(*hub)
    r = v.solve(1.0, 8.0, input_speed_rpm=114.0)
    assert r.clamp_law == "cam"  # the hub's [models] clamp_law, no keyword needed
    par = v.design.parasitic
    shell = 2 * palmgren_torque(W0, 300.0, 0.031, 110e-6, 1.5, 0.00025)
    driver = palmgren_torque(W0, 8.0 / par.sprocket_radius, 0.0235, 110e-6, 1.5, 0.00025)
    # the solved output speed is short of the creep-free one by the creep (~2 %)
    assert r.losses["hub_bearings"] == pytest.approx(float(shell + driver) * W0, rel=0.03)
    assert r.losses["hub_bearings"] > 0.0
    assert math.fsum(v for k, v in r.losses.items() if k != "total") == pytest.approx(
        r.losses["total"], rel=1e-12
    )
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-9)


def test_hub_bearings_off_for_the_paper_and_all_or_none(hub):
    design, fluid = load_builtin("table1")
    ball, d0, d2 = parasitic_torques(design, fluid, 200.0, 100.0, 600.0, 1e4, )
    assert not d0.any() and not d2.any()
    assert {"shell_bearings", "driver_bearing"} <= set(LOSS_TERMS.names())
    with pytest.raises(InputError, match="hub_bearing_f0"):
        parse_drive(edited("hub_bearing_f0 = 1.5", "# none"))
    half = hub[0].parasitic.model_dump()
    for key in ("hub_bearing_diameter", "driver_bearing_diameter", "wheel_load",
                "sprocket_radius", "hub_bearing_f0", "hub_bearing_f1", "hub_bearing_viscosity"):
        half.pop(key)
    assert not hub[0].replace(parasitic=half).parasitic.has_hub_bearings


# --- seals at the hub's size --------------------------------------------------------


def test_hub_seal_by_hand(hub):
    par = hub[0].parasitic
    m = seal_torque(par.seal_diameter, par.seal_k1, par.seal_beta, par.seal_k2)
    assert m == pytest.approx(1e-3 * (0.028 * 35.0**2.25 + 2.0), rel=1e-12)
    assert m == pytest.approx(0.0855, rel=1e-2)


# --- the cam's ramp hysteresis ------------------------------------------------------


def test_cam_loading_is_todays_law_and_unloading_clamps_harder(hub):
    design = hub[0]
    cam = design.cam
    loading = CamClamp.from_design(design)
    assert loading.branch == "loading"
    assert loading.gain == 1.0 / (
        cam.mean_radius * math.tan(cam.ramp_angle + math.atan(cam.friction))
    )
    unloading = CamClamp.from_design(design.replace(cam={**cam.model_dump(), "branch": "unloading"}))
    assert unloading.gain == pytest.approx(
        1.0 / (cam.mean_radius * math.tan(cam.ramp_angle - math.atan(cam.friction))), rel=1e-14
    )
    assert unloading.thrust(20.0) > loading.thrust(20.0)
    assert unloading.thrust(0.0) == loading.thrust(0.0) == cam.preload  # no torque, no band
    # without ramp friction the two branches agree
    assert CamClamp(1000.0, 0.1, 0.05, 0.0, branch="unloading").gain == CamClamp(
        1000.0, 0.1, 0.05, 0.0
    ).gain
    assert "branch" not in cam.model_dump()  # the default is not written


def test_a_self_locking_ramp_cannot_unload(hub):
    with pytest.raises(InputError, match="self-locks"):
        CamClamp(1000.0, math.atan(0.1) * 0.9, 0.05, 0.1, branch="unloading")
    with pytest.raises(InputError, match="self-locks"):
        parse_drive(edited('disc = "output"', 'disc = "output"\nbranch = "unloading"\n'
                                              "ramp_angle_deg = 0.2").replace(
            "ramp_angle_deg = 6.0", "# ramp", 1))
    with pytest.raises(InputError, match="branch"):
        CamClamp(1000.0, 0.1, 0.05, 0.005, branch="sideways")


def test_unloading_branch_solves_at_a_larger_force(hub):
    v = Variator(*hub)
    a = v.solve(1.0, 16.0, input_speed_rpm=114.0)
    b = v.with_cam({"branch": "unloading"}).solve(1.0, 16.0, input_speed_rpm=114.0)
    assert b.clamp_force > a.clamp_force
    assert b.eta == pytest.approx(b.eta_loss, abs=1e-9)


# --- a drive names its models -------------------------------------------------------


def test_the_paper_keeps_the_papers_models():
    design, fluid = load_builtin("table1")
    assert design.models is None and "models" not in design.model_dump()
    assert Variator().models == {
        "clamp_law": "constant", "traction_law": "isothermal",
        "lubrication": "full-film", "oil_temperature": "fixed",
    }
    with pytest.raises(InputError, match="clamp_force"):
        Variator().solve(1.0, 40.0, input_speed_rpm=2000)  # as before: the force is needed


def test_the_hub_names_its_models(hub):
    assert Variator(*hub).models["clamp_law"] == "cam"
    assert hub[0].models.given() == {
        "clamp_law": "cam",
        "traction_law": "isothermal",
        "lubrication": "mixed",
        "oil_temperature": "balance",
    }


def test_precedence_call_over_file_over_package(hub):
    design, fluid = hub
    assert effective_models(design, fluid)["clamp_law"] == "cam"
    assert effective_models(design, fluid, clamp_law="optimal")["clamp_law"] == "optimal"
    assert effective_models(design, fluid, clamp_force=1500.0)["clamp_law"] == "constant"
    assert effective_models(design, fluid, traction_law="thermal")["traction_law"] == "thermal"
    assert effective_models(design, fluid)["lubrication"] == "mixed"
    assert effective_models(design, fluid, lubrication="full-film")["lubrication"] == "full-film"
    v = Variator(*hub)
    assert v.solve(1.0, 8.0, clamp_force=1500.0, input_speed_rpm=114.0).clamp_law == "constant"
    with pytest.raises(InputError, match="one of"):
        effective_models(design, fluid, viscosity_model="x")


def test_traction_law_from_the_file_sets_the_fluid_and_flags_win():
    text = edited('traction_law = "isothermal"       # the paper', 'traction_law = "thermal" # t')
    design, fluid = parse_drive(text)
    assert fluid.traction_law == "thermal"
    assert Variator(design, fluid).fluid.traction_law == "thermal"
    assert Variator(design, fluid, traction_law="isothermal").fluid.traction_law == "isothermal"
    with pytest.raises(InputError, match="traction_law"):
        parse_drive(text.replace("[fluid]\n", '[fluid]\ntraction_law = "isothermal"\n'))


def test_models_are_checked_against_the_registries():
    with pytest.raises(InputError, match="one of: full-film"):
        parse_drive(edited('lubrication = "mixed" ', 'lubrication = "dry" '))
    with pytest.raises(InputError, match="clamp_law"):
        parse_drive(edited('clamp_law = "cam" ', 'clamp_law = "spring" '))
    with pytest.raises(InputError, match="operating"):
        parse_drive(edited("[operating]", '[operating]\nclamp_law = "constant"'))
    with pytest.raises(InputError, match="unknown"):
        parse_drive(edited("[models]", "[models]\nviscosity = \"walther\""))
    LUBRICATION_MODELS.register(ModelChoice("test-mixed", "a test entry"))
    try:
        design, _ = parse_drive(edited('lubrication = "mixed" ', 'lubrication = "test-mixed" '))
        assert Variator(design, load_builtin("hub")[1]).models["lubrication"] == "test-mixed"
    finally:
        LUBRICATION_MODELS.unregister("test-mixed")


def test_models_round_trip_through_a_file(hub, tmp_path):
    text = drive_to_toml(*hub, template=builtin_text("hub"))
    assert text == builtin_text("hub")
    design, _ = parse_drive(drive_to_toml(*load_builtin("table1")))
    assert design.models is None


def test_cli_reports_its_models_and_flags_win(capsys):
    assert main(["point", "--design", "hub", "--ratio", "1", "--torque", "8", "--speed",
                 "114", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["models"] == {"clamp_law": "cam", "traction_law": "isothermal",
                              "lubrication": "mixed", "oil_temperature": "balance"}
    assert data["clamp_law"] == "cam" and data["oil_temperature"] > 293.15  # the balance's
    assert main(["point", "--design", "hub", "--ratio", "1", "--torque", "8", "--speed",
                 "114", "--json", "--oil-temperature", "fixed"]) == 0
    fixed = json.loads(capsys.readouterr().out)
    assert fixed["models"]["oil_temperature"] == "fixed" and fixed["oil_model"] == "fixed"
    assert fixed["oil_temperature_C"] == pytest.approx(40.0)  # the fluid's own
    assert main(["point", "--design", "hub", "--ratio", "1", "--torque", "8", "--speed",
                 "114", "--clamp-law", "constant", "--traction-law", "thermal"]) == 0
    out = capsys.readouterr().out
    assert "models      clamp_law constant, traction_law thermal" in out
    d, f = open_drive("hub", "table1")
    assert f.traction_law == "isothermal"


def test_figure_titles_name_the_models_beyond_the_papers():
    import argparse

    from ballcvt.interfaces.cli.options import clamp_label

    hub = argparse.Namespace(design="hub", fluid=None, traction_law="thermal",
                             clamp_law="cam", clamp=None)
    assert clamp_label(hub) == "cam clamping, thermal traction, mixed lubrication, oil balance"
    hub.oil_temperature = "fixed"  # --oil-temperature wins over the drive file
    assert clamp_label(hub) == "cam clamping, thermal traction, mixed lubrication"
    hub.oil_temperature = 60.0
    assert clamp_label(hub) == "cam clamping, thermal traction, mixed lubrication, oil 60 C"
    paper = argparse.Namespace(design=None, fluid=None, traction_law=None,
                               clamp_law="constant", clamp=None)
    assert clamp_label(paper) == "$F_{N0}$ = 2000 N"
