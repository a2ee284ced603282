"""Figures are checked, not only run: every labelled line has data that can be drawn, and
nothing is filled outside the data given (tools/figcheck.py; the docs build applies the
same check to every gallery figure).

The gallery examples are executed here with the Agg backend (a few seconds each), and
every figure function of ``ballcvt.plotting`` is drawn from a small sweep or synthetic data.
"""

import runpy
import types
from pathlib import Path

import matplotlib
import numpy as np
import pandas as pd
import pytest
import xarray as xr

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from figcheck import problems  # noqa: E402  (tools/figcheck.py)
from matplotlib.figure import Figure  # noqa: E402

import ballcvt.plotting as bp  # noqa: E402
from ballcvt.errors import InputError  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GALLERY = sorted((ROOT / "examples" / "gallery").glob("plot_*.py"))
TORQUES = [20.0, 60.0, 100.0]  # the sweep ends at 100 N m: limits 160, 131 and 97 N m


@pytest.fixture(scope="module")
def sweep(double):
    return double.sweep(ratio=[0.8, 1.2, 1.6], output_torque=TORQUES, clamp_force=2000.0,
                        input_speed_rpm=2000, progress=False)


@pytest.fixture(scope="module")
def both(double):
    return double.sweep(ratio=[0.8, 1.6], output_torque=[40.0], clamp_force=2000.0,
                        input_speed_rpm=2000, architecture=("double", "single"),
                        progress=False)


@pytest.mark.parametrize("path", GALLERY, ids=lambda p: p.stem)
def test_gallery_example_draws_its_data(path, monkeypatch):
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    monkeypatch.chdir(path.parent)
    plt.close("all")
    runpy.run_path(str(path), run_name="__main__")
    figs = [plt.figure(n) for n in plt.get_fignums()]
    assert figs, f"{path.name} draws no figure"
    found = [f"{path.name}: {p}" for fig in figs for p in problems(fig)]
    plt.close("all")
    assert not found, "\n".join(found)


def test_the_checker_sees_an_empty_labelled_line_and_a_map_beyond_its_data():
    fig = Figure()
    ax = fig.add_subplot()
    ax.plot([0, 1], [np.nan, np.nan], label="double idler")
    ax.plot([0, 1], [1, 2], label="single idler")
    assert problems(fig) == ["axes 0 (''): the line labelled 'double idler' has no point "
                             "that can be drawn"]
    fig = Figure()
    ax = fig.add_subplot()
    ax.contourf([0, 1, 2], [0, 10, 20], np.ones((3, 3)) * [[0.8], [0.85], [0.9]])
    assert problems(fig, box=(0, 2, 0, 10)) != []


def test_efficiency_map_draws_nothing_beyond_the_sweep(sweep):
    """The sweep ends at 100 N m, its limit is higher at two of its ratios: no contour
    above 100 N m nor above the limit, the band between hatched as not computed, the region
    above the limit hatched."""
    fig = Figure()
    ax = fig.add_subplot()
    art = bp.plot_efficiency_map(sweep, ax=ax)
    one = sweep.squeeze(drop=True)
    assert float(one.limit_torque.max()) > max(TORQUES) > float(one.limit_torque.min())
    assert problems(fig, box=(0.8, 1.6, min(TORQUES), max(TORQUES))) == []
    labels = ax.get_legend_handles_labels()[1]
    assert "beyond the limiting torque" in labels
    assert "not computed (the sweep ends at 100 N m)" in labels
    assert len(art["outside"]) == 2
    assert "NuVinci" in ax.get_title() and "2000 rpm" in ax.get_title()


def test_efficiency_map_file_figure_stays_inside_its_data(sweep):
    one = sweep.squeeze(drop=True)
    fig = bp.efficiency_map(one.ratio.values, one.output_torque.values, one.eta.values,
                            one.limit_torque.values, title=bp.map_title(sweep),
                            limit_eta=one.eta_at_limit.values)
    assert problems(fig, box=(0.8, 1.6, min(TORQUES), max(TORQUES))) == []
    assert fig.axes[0].get_title().startswith(sweep.attrs["design_name"])


def test_efficiency_map_of_two_clamp_forces_is_refused_in_one_line(sweep):
    two = xr.concat([sweep, sweep.assign_coords(clamp_force=[3000.0])], "clamp_force")
    with pytest.raises(InputError) as err:
        bp.plot_efficiency_map(two, ax=Figure().add_subplot())
    message = str(err.value)
    assert "\n" not in message and "clamp_force" in message
    assert "sweep.sel(clamp_force=2000.0)" in message


def test_plot_curves_skips_combinations_without_data(both):
    fig = Figure()
    lines = bp.plot_curves(both.sel(output_torque=40.0), y="creep", x="ratio",
                           ax=fig.add_subplot())
    assert len(lines) == 7  # 4 contacts of the double idler + 3 of the single (not 10)
    assert problems(fig) == []


def _cycle_steps():
    t = np.linspace(0.0, 10.0, 11)
    steps = pd.DataFrame({"time": t, "ratio": 1.0 + 0.05 * t, "input_speed_rpm": 2000.0,
                          "output_speed_rpm": 2000.0 * (1.0 + 0.05 * t), "eta": 0.9,
                          "flag": ["ok"] * 10 + ["beyond_capacity"]})
    for kind in ("creep", "spin", "bearing", "parasitic"):
        steps[f"loss_{kind}"] = 10.0 + t
    steps.loc[10, "eta"] = np.nan
    return steps


def _shift_samples(moments=True):
    t = np.linspace(0.0, 0.6, 13)
    hold = np.full(t.size, 0.4 if moments else np.nan)
    return pd.DataFrame({"time_s": t, "ratio": 0.5 + 2.0 * t, "tilt_deg": -18.0 + 60.0 * t,
                         "holding_moment_Nm": hold, "shifter_moment_Nm": 8 * hold,
                         "eta": 0.9 + 0.01 * t})


def _curve(law):
    s = np.linspace(0.0, 0.05, 20)
    return types.SimpleNamespace(creep=s, mu=0.08 * np.tanh(100 * s), chi=0.01 * s,
                                 temperature_rise=np.zeros_like(s) + (law == "thermal") * s,
                                 law=law)


def _study():
    n = 8
    rng = np.random.default_rng(0)
    ds = xr.Dataset({"eta": ("design", 0.8 + 0.1 * rng.random(n)),
                     "mass": ("design", 1.0 + rng.random(n)),
                     "roller_radius": ("design", 0.02 + 0.01 * rng.random(n)),
                     "aspect_ratio": ("design", 1.5 + rng.random(n)),
                     "status": ("design", np.array([0] * 6 + [1] * 2)),
                     "pareto": ("design", np.array([True, True, False, False, True] + [False] * 3)),
                     "chosen": ("design", np.array([True] + [False] * 7))},
                    coords={"design": np.arange(n)})
    return ds


def _figures(sweep, both):
    """Every figure function of ballcvt.plotting, drawn (name -> Figure)."""
    one = sweep.squeeze(drop=True)
    arrays = (one.ratio.values, one.output_torque.values, one.eta.values,
              one.limit_torque.values)
    fit = types.SimpleNamespace(model=np.linspace(0.0, 0.08, 20), residuals=np.zeros(20),
                                rms=0.0)
    measured = types.SimpleNamespace(condition=np.array(["a"] * 10 + ["b"] * 10),
                                     creep=np.tile(np.linspace(0.0, 0.05, 10), 2),
                                     mu=np.linspace(0.0, 0.08, 20))

    def on_axes(draw):
        fig = Figure()
        draw(fig.add_subplot())
        return fig

    tilt = np.linspace(-30.0, 30.0, 13)
    return {
        "cycle_figure": bp.cycle_figure(_cycle_steps()),
        "shift_figure": bp.shift_figure(_shift_samples()),
        "capacity_figure": bp.capacity_figure(pd.DataFrame({
            "ratio": [0.6, 1.0, 1.6], "limit_torque": [120.0, 160.0, 90.0],
            "lowest_torque": [0.0, 0.0, 5.0],
            "active_constraint": ["creep (output contact)", "pressure (max_pressure 3 GPa)",
                                  "creep (input contact)"]})),
        "line_panels": bp.line_panels([{"ylabel": "eta", "lines": [
            (one.output_torque.values, one.eta.sel(ratio=1.2).values, "1.2", None)]}], "T"),
        "efficiency_map": bp.efficiency_map(*arrays, limit_eta=one.eta_at_limit.values),
        "draw_efficiency_map": on_axes(lambda ax: bp.draw_efficiency_map(ax, *arrays)),
        "plot_efficiency_map": on_axes(lambda ax: bp.plot_efficiency_map(sweep, ax=ax)),
        "draw_life_contours": on_axes(lambda ax: bp.draw_life_contours(
            ax, one.ratio.values, one.output_torque.values,
            10.0 ** np.add.outer(np.linspace(2.0, 5.0, one.ratio.size),
                                 -np.linspace(0.0, 1.0, one.output_torque.size)))),
        "shift_effort_map": bp.shift_effort_map(
            one.ratio.values, one.output_torque.values,
            np.add.outer(np.linspace(1.0, 2.0, one.ratio.size),
                         np.linspace(0.0, 3.0, one.output_torque.size)),
            one.limit_torque.values),
        "plot_curves": on_axes(lambda ax: bp.plot_curves(both, y="eta", x="ratio", ax=ax)),
        "ratio_vs_tilt": bp.ratio_vs_tilt([(tilt, np.exp(tilt / 30), "45 deg",
                                            np.abs(tilt) < 25)]),
        "fit_figure": bp.fit_figure(measured, fit),
        "maps_figure": bp.maps_figure(sweep, sweep, ["base", "chosen"]),
        "parameters_figure": bp.parameters_figure(_study(), ["roller_radius", "aspect_ratio"],
                                                  "eta"),
        "pareto_figure": bp.pareto_figure(_study(), ["eta", "mass"], {"mass": "kg"}),
        "plot_traction_curve": on_axes(lambda ax: bp.plot_traction_curve(_curve("isothermal"),
                                                                         ax)),
        "traction_curve_figure": bp.traction_curve_figure([_curve("isothermal"),
                                                           _curve("thermal")]),
        "uncertainty_figure": bp.uncertainty_figure(*_uncertainty()),
    }


def _uncertainty():
    """A band and a ranking as `UncertaintyResult.band` and `ranking` give them."""
    outputs = ["eta at ratio 0.5, P 100 W, 114 rpm", "eta at ratio 1, P 100 W, 114 rpm",
               "capacity at ratio 1, 114 rpm"]
    band = pd.DataFrame({"output": outputs, "unit": ["-", "-", "N m"],
                         "nominal": [0.9, 0.93, 380.0], "q05": [0.88, np.nan, 270.0],
                         "q50": [0.9, np.nan, 390.0], "q95": [0.92, np.nan, 500.0]})
    ranking = pd.DataFrame({"score_eta": [0.5, 0.2, 0.0], "score_capacity": [0.1, 0.9, np.nan],
                            outputs[0]: [0.5, -0.2, 0.0], outputs[1]: [np.nan] * 3,
                            outputs[2]: [0.1, 0.9, np.nan]},
                           index=["design.cam.preload", "design.cam.ramp_angle_deg",
                                  "fluid.density"])
    return band, ranking


def test_every_figure_function_draws_its_data(sweep, both):
    figures = _figures(sweep, both)
    drawing = {name for name in bp.__all__ if name not in ("LABELS", "save", "map_title")}
    assert set(figures) == drawing, "a figure function of ballcvt.plotting is not checked"
    found = [f"{name}: {p}" for name, fig in figures.items()
             for p in problems(fig, box=(0.8, 1.6, min(TORQUES), max(TORQUES))
                               if "map" in name else None)]
    assert not found, "\n".join(found)


def test_shift_figure_without_moments_draws_no_empty_line():
    fig = bp.shift_figure(_shift_samples(moments=False))
    assert problems(fig) == []
    assert "no shift-moment model" in [t.get_text() for t in fig.axes[1].texts]
