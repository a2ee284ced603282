"""The efficiency-optimal clamp (docs/model.md §11) at zero output torque and without a
pressure limit (issue 23)."""

import math

import numpy as np
import pytest

from ballcvt import InputError, Variator
from ballcvt.interfaces.cli import main as cli
from ballcvt.model.clamping import OptimalClamp
from drives import fixed_oil_hub

RPM = 2000.0


@pytest.fixture(scope="module")
def v():
    return Variator()


@pytest.fixture(scope="module")
def unbounded(v):
    """The Table I drive with no pressure limit."""
    return Variator(design=v.design.model_copy(update={"max_pressure": math.inf}), fluid=v.fluid)


def test_zero_torque_is_the_least_clamp_holding_the_drag(v):
    zero = v.optimal_clamp_force(1.0, 0.0, input_speed_rpm=RPM)
    tiny = v.optimal_clamp_force(1.0, 1e-3, input_speed_rpm=RPM)
    assert zero.eta == 0.0 and zero.max_creep <= v.design.creep_limit
    assert zero.clamp_force == pytest.approx(tiny.clamp_force)  # the limit as T2 -> 0
    assert zero.clamp_force == OptimalClamp().min_force
    r = v.solve(1.0, 0.0, clamp_law="optimal", input_speed_rpm=RPM)
    assert r.clamp_force == pytest.approx(zero.clamp_force) and r.clamp_law == "optimal"
    with pytest.raises(InputError, match=">= 0 N m"):
        v.optimal_clamp_force(1.0, -1.0, input_speed_rpm=RPM)


def test_zero_torque_creep_bound_is_bisected(v):
    """With a floor below the drag's needs, the answer is the creep-limited force."""
    from ballcvt.solvers.optimal_clamp import ClampCase, clamp_optimum

    case = ClampCase(v.design, v.fluid, "double", 1.0, 0.0, RPM * math.pi / 30)
    opt = clamp_optimum(case, OptimalClamp(creep_limit=0.002, min_force=1.0))
    assert opt.active == "creep" and opt.max_creep <= 0.002
    assert opt.max_creep == pytest.approx(0.002, rel=0.05)


def test_sweep_from_zero_torque(v):
    ds = v.sweep(ratio=[0.8, 1.2], output_torque=[0.0, 20.0], clamp_law="optimal",
                 input_speed_rpm=RPM)
    assert np.all(np.isfinite(ds.clamp_force.values))
    assert int(ds.status.max()) == 0


def test_cli_table_and_map_with_the_optimal_law(tmp_path):
    assert cli.main(["table", "--clamp-law", "optimal", "--n-ratio", "2", "--n-torque", "2",
                     "--n-speed", "2", "--out", str(tmp_path / "t"), "--quiet"]) == 0
    assert cli.main(["map", "--clamp-law", "optimal", "--n-ratio", "2", "--n-torque", "2",
                     "--out", str(tmp_path / "m"), "--quiet"]) == 0


def test_no_pressure_limit(v, unbounded):
    """max_pressure = inf: the design is accepted and the optimum is found without a
    pressure bound (here it never sat on it, so it is the bounded one)."""
    bounded = v.optimal_clamp_force(1.0, 10.0, input_speed_rpm=RPM)
    free = unbounded.optimal_clamp_force(1.0, 10.0, input_speed_rpm=RPM)
    assert free.clamp_force == pytest.approx(bounded.clamp_force, abs=2 * OptimalClamp().xtol)
    assert free.eta == pytest.approx(bounded.eta, abs=1e-8) and free.active != "pressure"
    law = v.optimal_clamp_force(1.0, 10.0, input_speed_rpm=RPM, max_pressure=math.inf)
    assert law.clamp_force == pytest.approx(free.clamp_force, abs=2 * OptimalClamp().xtol)
    assert unbounded.optimal_clamp_force(1.0, 0.0, input_speed_rpm=RPM).clamp_force > 0


def test_pressure_limit_that_binds_the_optimum(v):
    """A tight limit still caps the force (its grid searched in one span as before)."""
    free = v.optimal_clamp_force(1.0, 60.0, input_speed_rpm=RPM)
    tight = v.optimal_clamp_force(1.0, 60.0, input_speed_rpm=RPM,
                                  max_pressure=0.999 * free.max_pressure)
    assert tight.max_pressure <= 0.999 * free.max_pressure * (1 + 1e-9)
    with pytest.raises(InputError, match="max_pressure"):
        v.optimal_clamp_force(1.0, 10.0, input_speed_rpm=RPM, max_pressure=float("nan"))


def test_cycle_steps_at_zero_torque():
    """An input-side cycle whose power cannot drive the drag ends at zero output torque:
    the optimal law answers it (flagged power_below_drag, not an error)."""
    from ballcvt import load_builtin
    from ballcvt.analysis.cycle_files import cycle_from_arrays
    from ballcvt.analysis.cycles import run_cycle

    rig = cycle_from_arrays(time=[0.0, 1.0, 2.0], input_speed=np.full(3, RPM * math.pi / 30),
                            input_power=[3000.0, 300.0, 300.0], ratio=[1.0, 1.0, 1.0])
    res = run_cycle(Variator(*fixed_oil_hub()), rig, clamp_law="optimal", progress=False)
    assert list(res.steps["flag"]) == ["ok", "power_below_drag", "power_below_drag"]
    assert np.all(res.steps["clamp_force"] > 0)
