"""Issue 25: losses are components plus exactly one total (no subtotal counted twice)."""

import math
from pathlib import Path

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.api import load_builtin
from ballcvt.errors import BallCVTDeprecationWarning
from ballcvt.results.losses import LOSS_SUBTOTALS, LossBreakdown
from ballcvt.results.point import OperatingResult
from drives import fixed_oil_hub

COMPONENTS = {"creep", "spin", "roller_bearings", "idler_bearings", "churning", "seals",
              "disc_bearings", "hub_bearings"}  # hub_bearings: the hub's own (issue 27)


@pytest.fixture(scope="module")
def hub():
    return Variator(*fixed_oil_hub())


def test_random_points_components_sum_to_total(hub):
    rng = np.random.default_rng(25)
    for _ in range(6):
        r = hub.solve(float(rng.uniform(0.6, 1.6)), float(rng.uniform(5.0, 60.0)),
                      clamp_force=float(rng.uniform(1500.0, 3000.0)),
                      input_speed_rpm=float(rng.uniform(500.0, 3000.0)))
        assert set(r.losses) == COMPONENTS | {"total"}
        parts = [v for k, v in r.losses.items() if k != "total"]
        assert math.fsum(parts) == pytest.approx(r.losses["total"], rel=1e-12)
        # summing the mapping counts every loss once, and the total once
        assert math.fsum(r.losses.values()) == pytest.approx(2 * r.losses["total"], rel=1e-12)
        assert r.losses.parasitic > 0.0  # the hub's parasitic losses are components


def test_old_subtotal_keys_still_answer_with_a_warning(hub):
    r = hub.solve(1.0, 30.0, clamp_force=2000.0, input_speed_rpm=2000)
    import ballcvt._compat as compat
    compat._warned.difference_update({f"losses['{k}']" for k in LOSS_SUBTOTALS})
    with pytest.warns(BallCVTDeprecationWarning, match=r"losses\['bearing'\].*losses.bearing"):
        bearing = r.losses["bearing"]
    assert bearing == r.losses["roller_bearings"] + r.losses["idler_bearings"]
    assert r.losses.parasitic == pytest.approx(
        r.losses["churning"] + r.losses["seals"] + r.losses["disc_bearings"]
        + r.losses["hub_bearings"])
    assert "bearing" not in r.losses and "parasitic" not in dict(r.losses)
    assert r.to_dict()["loss_subtotals"]["bearing"] == r.losses.bearing


def test_saved_results_round_trip_and_old_files_load(hub, tmp_path):
    r = hub.solve(1.0, 30.0, clamp_force=2000.0, input_speed_rpm=2000)
    back = OperatingResult.from_dict(r.to_dict())
    assert dict(back.losses) == dict(r.losses)
    old = r.to_dict()  # a file of an earlier release: subtotals among the keys
    old["losses"] = {**old["losses"], "bearing": r.losses.bearing,
                     "parasitic": r.losses.parasitic}
    assert set(OperatingResult.from_dict(old).losses) == COMPONENTS | {"total"}


def test_loss_breakdown_drops_subtotals():
    b = LossBreakdown({"creep": 1.0, "spin": 2.0, "roller_bearings": 3.0,
                       "idler_bearings": 4.0, "bearing": 7.0, "parasitic": 0.0})
    assert dict(b) == {"creep": 1.0, "spin": 2.0, "roller_bearings": 3.0,
                       "idler_bearings": 4.0, "total": 10.0}


def test_cycle_losses_are_components_and_one_total():
    tiny = Path(__file__).parent / "data" / "tiny_cycle.csv"
    from ballcvt.api import read_cycle
    v = Variator(*fixed_oil_hub())
    s = v.run_cycle(read_cycle(tiny), clamp_force=2000.0).summary
    lj = s["losses_J"]
    assert "bearing" not in lj and "parasitic" not in lj
    assert math.fsum(x for k, x in lj.items() if k != "total") == pytest.approx(
        lj["total"], rel=1e-12)
    assert s["loss_subtotals_J"]["bearing"] == pytest.approx(
        lj["roller_bearings"] + lj["idler_bearings"])


def test_sweep_loss_components_sum_to_total(hub):
    from ballcvt.analysis.sweeps.variables import LOSS_COMPONENTS
    ds = hub.sweep(ratio=[0.7, 1.3], output_torque=[10.0, 40.0], clamp_force=2500.0,
                   input_speed_rpm=1500)
    parts = ds.losses.sel(loss=list(LOSS_COMPONENTS)).sum("loss")
    total = ds.losses.sel(loss="total")
    ok = ds.status == 0
    assert bool(ok.any())
    assert np.allclose(parts.where(ok), total.where(ok), rtol=1e-12, equal_nan=True)
    # the loss axis is the components and one total: summing it counts each loss twice
    # only through total itself (issue 25: no subtotal on the axis)
    assert list(ds.loss.values) == [*LOSS_COMPONENTS, "total"]
    both = ds.losses.where(ok).sum("loss") - 2.0 * total.where(ok)
    assert np.allclose(both.where(ok), 0.0, atol=1e-9 * float(total.where(ok).max()))
    assert list(ds.subtotal.values) == ["bearing", "parasitic"]
