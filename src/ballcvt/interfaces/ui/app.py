"""Interactive explorer in the browser (Bokeh server): ``ballcvt explore-ui``.

Sliders set the operating point (ideal ratio, output torque, clamping force, input speed)
and the main design parameters (ball radius, aspect ratio, number of balls, contact
angle). The page shows the operating point (efficiency, the losses as a breakdown, creeps,
peak pressures and films per contact), the efficiency map with the point on it and the
limiting-torque curve. A clamping-law menu picks the constant force (the slider), the
design's loading cam or the efficiency-optimal force. The page opens where the drive runs
(its ``[operating]`` table: input speed, ratio range, clamping law and force), else at the
paper's point. A point is one `Variator.solve` (a few milliseconds); the map and
the limits are recomputed when the design, the clamping force or the speed change (about
half a second, on the fast batched paths). Every figure shown is also in a hidden element
(``.bcvt-state``) as JSON, so that tests can compare it with the Python API.
"""

from __future__ import annotations

import html
import json
from typing import Any

import numpy as np

from ...api import PAPER_POINT, Variator, drive_clamp, operating_ratio_range
from ...errors import BallCVTError
from ...params import Design, Fluid
from ...registry import CLAMP_LAWS

__all__ = ["make_document", "serve", "SLIDERS", "MAP_GRID"]

#: Slider name -> (title, start, end, step, unit); operating point first, then design.
SLIDERS = {
    "ratio": ("ideal ratio tau_ID", 0.5, 2.0, 0.01, "-"),
    "output_torque": ("output torque T_2", 0.0, 160.0, 1.0, "N m"),
    "clamp_force": ("clamping force F_N0", 500.0, 4000.0, 50.0, "N"),
    "input_speed_rpm": ("input speed", 200.0, 4000.0, 50.0, "rpm"),
    "roller_radius_mm": ("ball radius r_S", 20.0, 40.0, 0.5, "mm"),
    "aspect_ratio": ("aspect ratio k", 1.3, 2.2, 0.05, "-"),
    "n_rollers": ("number of balls n", 5, 10, 1, ""),
    "theta0_deg": ("input contact angle", 35.0, 55.0, 1.0, "deg"),
}
DESIGN_SLIDERS = ("roller_radius_mm", "aspect_ratio", "n_rollers", "theta0_deg")
#: Efficiency map grid (ratios x torques).
MAP_GRID = (12, 12)


class _State:
    """The current inputs, the variator built from them, and what is shown."""

    def __init__(self, design: Design, fluid: Fluid, architecture: str):
        self.base, self.fluid, self.architecture = design, fluid, architecture
        op = design.operating
        given = {} if op is None else op.model_dump(exclude_none=True)
        #: Clamping law: a name of `ballcvt.registry.CLAMP_LAWS` (the constant force: slider).
        self.clamp_law: str = drive_clamp(design)[0] or "constant"  # [models], [operating]
        lo, hi = given.get("ratio_range", (0.5, 2.0))
        self.values: dict[str, float] = {
            "ratio": min(max(PAPER_POINT.ratio, lo), hi),
            "output_torque": PAPER_POINT.output_torque,
            "clamp_force": given.get("clamp_force", PAPER_POINT.clamp_force),
            "input_speed_rpm": given.get("input_speed_rpm", PAPER_POINT.input_speed_rpm),
            "roller_radius_mm": design.roller_radius * 1e3,
            "aspect_ratio": design.aspect_ratio,
            "n_rollers": design.n_rollers,
            "theta0_deg": design.theta0_deg,
        }
        self.variator: Variator | None = None
        self.message = ""

    def design(self) -> Design:
        v = self.values
        return self.base.replace(
            roller_radius=v["roller_radius_mm"] / 1e3,
            aspect_ratio=float(v["aspect_ratio"]),
            n_rollers=int(v["n_rollers"]),
            theta0_deg=float(v["theta0_deg"]),
        )

    def rebuild(self) -> None:
        """A new variator from the design sliders (None with a message if not buildable)."""
        try:
            self.variator = Variator(self.design(), self.fluid, self.architecture)
            self.message = ""
        except BallCVTError as exc:
            self.variator, self.message = None, str(exc)

    def clamp(self) -> dict[str, Any]:
        """``clamp_force`` (constant law, the slider) or ``clamp_law`` of the API calls."""
        if self.clamp_law == "constant":
            return {"clamp_force": float(self.values["clamp_force"])}
        return {"clamp_law": self.clamp_law}

    def slider_range(self, name: str) -> tuple[float, float, float]:
        """(start, end, step) of a slider: `SLIDERS`', or around the drive's operating
        speeds and over its operating ratios."""
        start, end, step = SLIDERS[name][1:4]
        op = self.base.operating
        if name == "input_speed_rpm" and op is not None and op.speed_range_rpm is not None:
            lo, hi = op.speed_range_rpm
            return 0.5 * lo, max(2.0 * hi, float(self.values[name])), 5.0
        if name == "ratio" and op is not None and op.ratio_range is not None:
            return float(op.ratio_range[0]), float(op.ratio_range[1]), step
        return start, end, step

    def point(self) -> dict[str, Any]:
        """Solve the current point: the figures shown (``eta`` None with a message)."""
        v = self.values
        out: dict[str, Any] = {
            "inputs": {k: float(v[k]) for k in SLIDERS},
            "clamp_law": self.clamp_law,
            "design": None if self.variator is None else self.variator.design.model_dump(),
            "architecture": self.architecture,
            "eta": None,
            "message": self.message,
        }
        if self.variator is None:
            return out
        try:
            r: Any = self.variator.solve(
                ratio=float(v["ratio"]),
                output_torque=float(v["output_torque"]),
                input_speed_rpm=float(v["input_speed_rpm"]),
                **self.clamp(),
            )
        except BallCVTError as exc:
            out["message"] = str(exc)
            return out
        out.update(
            eta=r.eta,
            input_power=r.input_power,
            losses={k: float(x) for k, x in r.losses.items()},
            contacts={
                k: {
                    "creep": c.creep,
                    "p_max": c.p_max,
                    "film_thickness": c.film_thickness,
                }
                for k, c in r.contacts.items()
            },
            warnings=list(r.warnings),
        )
        return out

    def map(self) -> dict[str, Any] | None:
        """Efficiency map and limiting-torque curve of the current design, force, speed."""
        if self.variator is None:
            return None
        v = self.values
        lo, hi = operating_ratio_range(self.base)
        lo, hi = (lo, hi) if self.base.operating is not None else (max(lo, 0.5), min(hi, 2.0))
        ratio = np.linspace(lo, hi, MAP_GRID[0])
        kw: dict[str, Any] = {**self.clamp(), "input_speed_rpm": v["input_speed_rpm"]}
        var, n = self.variator, ratio.size
        try:
            # one limit search for the whole map, handed to the sweep; the torque axis
            # reaches past the limits at both ends and in the middle of the ratio range
            search = var.limit_curve(
                ratio, input_speed_rpm=float(v["input_speed_rpm"]), progress=False, **self.clamp()
            )
            ends = [0, n - 1, n // 2]
            for i in ends:
                if np.isnan(search.torque[i]):  # no limit: the point's own search says why
                    var.limit_torque(ratio=float(ratio[i]), **kw)
            top = float(max(search.torque[ends]))
            torque = np.linspace(0.02 * top, 1.05 * top, MAP_GRID[1])
            ds = var.sweep(ratio=ratio, output_torque=torque, limit_torque=search, **kw).squeeze(
                drop=True
            )
        except BallCVTError as exc:
            self.message = str(exc)
            return None
        return {
            "ratio": ratio,
            "torque": torque,
            "eta": ds.eta.transpose("output_torque", "ratio").values,
            "limit": ds.limit_torque.values,
        }


#: Loss kinds shown as bars.
KINDS = ["creep", "spin", "roller_bearings", "idler_bearings", "parasitic"]


def _sliders(state: _State) -> dict:
    """One Bokeh slider per entry of `SLIDERS`, at the state's values."""
    from bokeh.models import Slider

    sliders = {}
    for name, (title, *_, unit) in SLIDERS.items():
        start, end, step = state.slider_range(name)
        sliders[name] = Slider(
            title=f"{title} [{unit}]" if unit else title,
            start=start,
            end=end,
            step=step,
            value=state.values[name],
            name=name,
            css_classes=[f"bcvt-slider-{name}"],
            width=320,
            disabled=name == "clamp_force" and state.clamp_law != "constant",
        )
    return sliders


def _law_menu(state: _State):
    """The clamping-law menu (`ballcvt.registry.CLAMP_LAWS`), at the state's law."""
    from bokeh.models import Select

    return Select(
        title="clamping law",
        value=state.clamp_law,
        options=list(CLAMP_LAWS.names()),
        name="clamp_law",
        css_classes=["bcvt-clamp-law"],
        width=320,
    )


def _contact_table(source):
    """Table of creep, peak pressure and film thickness per contact."""
    from bokeh.models import DataTable, TableColumn

    return DataTable(
        source=source,
        columns=[
            TableColumn(field="contact", title="contact"),
            TableColumn(field="creep", title="creep [-]"),
            TableColumn(field="p_max", title="p_max [GPa]"),
            TableColumn(field="film", title="film [um]"),
        ],
        width=420,
        height=150,
        index_position=None,
    )


def _map_figure(map_src, limit_src, point_src):
    """Efficiency map with the limiting-torque curve and the operating point."""
    from bokeh.models import ColorBar, LinearColorMapper
    from bokeh.palettes import Viridis256
    from bokeh.plotting import figure

    mapper = LinearColorMapper(palette=Viridis256, low=0.5, high=0.95, nan_color="white")
    emap = figure(
        height=420,
        width=560,
        title="efficiency map (white: beyond the limiting torque)",
        x_axis_label="ideal ratio tau_ID [-]",
        y_axis_label="output torque T_2 [N m]",
    )
    emap.image(image="image", x="x", y="y", dw="dw", dh="dh", source=map_src, color_mapper=mapper)
    emap.line("ratio", "limit", source=limit_src, color="red", line_width=2, legend_label="limit")
    emap.scatter("ratio", "torque", source=point_src, size=12, color="black", marker="x")
    emap.add_layout(ColorBar(color_mapper=mapper, title="eta"), "right")
    return emap


class _View:
    """The page's widgets and the data sources they draw from."""

    def __init__(self):
        from bokeh.models import ColumnDataSource, Div
        from bokeh.plotting import figure

        self.eta = Div(text="", css_classes=["bcvt-eta"], styles={"font-size": "28px"})
        self.message = Div(
            text="", css_classes=["bcvt-message"], styles={"color": "#a00"}, width=640
        )
        self.state = Div(text="", css_classes=["bcvt-state"], visible=False)
        self.loss_src = ColumnDataSource({"kind": [], "watts": []})
        self.losses = figure(
            x_range=KINDS, height=260, width=420, title="losses [W]", toolbar_location=None
        )
        self.losses.vbar(x="kind", top="watts", source=self.loss_src, width=0.7)
        self.contact_src = ColumnDataSource({"contact": [], "creep": [], "p_max": [], "film": []})
        self.table = _contact_table(self.contact_src)
        self.map_src = ColumnDataSource({"image": [], "x": [], "y": [], "dw": [], "dh": []})
        self.limit_src = ColumnDataSource({"ratio": [], "limit": []})
        self.point_src = ColumnDataSource({"ratio": [], "torque": []})
        self.emap = _map_figure(self.map_src, self.limit_src, self.point_src)

    def show_point(self, p: dict[str, Any]) -> None:
        """Show an operating point (`_State.point`)."""
        if p["eta"] is None:
            self.eta.text = "efficiency: <span class='bcvt-value'>n/a</span>"
        else:
            self.eta.text = f"efficiency: <span class='bcvt-value'>{p['eta']:.4f}</span>"
            lw = p["losses"]
            self.loss_src.data = {"kind": KINDS, "watts": [lw.get(k, 0.0) for k in KINDS]}
            cs = p["contacts"]
            self.contact_src.data = {
                "contact": list(cs),
                "creep": [f"{c['creep']:.3e}" for c in cs.values()],
                "p_max": [f"{c['p_max'] / 1e9:.3f}" for c in cs.values()],
                "film": [f"{c['film_thickness'] * 1e6:.3f}" for c in cs.values()],
            }
        self.message.text = p["message"] + (
            " " + " ".join(p.get("warnings", [])) if p.get("warnings") else ""
        )
        self.point_src.data = {
            "ratio": [p["inputs"]["ratio"]],
            "torque": [p["inputs"]["output_torque"]],
        }
        self.state.text = (
            "<pre class='bcvt-json'>" + html.escape(json.dumps(p, default=float)) + "</pre>"
        )

    def show_map(self, m: dict[str, Any] | None) -> None:
        """Show an efficiency map (`_State.map`; None clears it)."""
        if m is None:
            self.map_src.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
            self.limit_src.data = {"ratio": [], "limit": []}
            return
        r, t = m["ratio"], m["torque"]
        self.map_src.data = {
            "image": [m["eta"]],
            "x": [r[0]],
            "y": [t[0]],
            "dw": [r[-1] - r[0]],
            "dh": [t[-1] - t[0]],
        }
        self.limit_src.data = {"ratio": list(r), "limit": [float(x) for x in m["limit"]]}


def make_document(doc, design: Design, fluid: Fluid, architecture: str = "double") -> None:
    """Fill a Bokeh document with the explorer (one per browser session)."""
    from bokeh.layouts import column, row
    from bokeh.models import Div

    state = _State(design, fluid, architecture)
    state.rebuild()
    sliders = _sliders(state)
    law = _law_menu(state)
    view = _View()

    def on_law(new: str) -> None:
        state.clamp_law = new
        sliders["clamp_force"].disabled = new != "constant"
        view.show_point(state.point())
        view.show_map(state.map())

    law.on_change("value", lambda _a, _o, new: on_law(new))

    def on_point(name: str, new) -> None:
        state.values[name] = new
        view.show_point(state.point())

    def on_map(name: str, new) -> None:
        state.values[name] = new
        if name in DESIGN_SLIDERS:
            state.rebuild()
        view.show_point(state.point())
        view.show_map(state.map())

    for name, s in sliders.items():
        if name not in DESIGN_SLIDERS:  # the point follows the slider as it moves
            s.on_change("value", lambda _a, _o, new, name=name: on_point(name, new))
        if name not in ("ratio", "output_torque"):
            # a new design or map on release (value_throttled): half a second per change
            s.on_change("value_throttled", lambda _a, _o, new, name=name: on_map(name, new))
    view.show_point(state.point())
    view.show_map(state.map())
    title = Div(
        text=f"<h2>ballcvt explorer</h2><p>{design.name}; fluid: {fluid.name}; "
        f"{architecture} idler; {fluid.traction_law} traction law</p>",
        width=900,
    )
    doc.add_root(
        column(
            title,
            row(
                column(law, *sliders.values()),
                column(view.eta, view.losses, view.table),
                view.emap,
            ),
            view.message,
            view.state,
        )
    )
    doc.title = "ballcvt explorer"


def serve(
    design: Design,
    fluid: Fluid,
    *,
    architecture: str = "double",
    port: int = 5006,
    address: str = "127.0.0.1",
    show: bool = False,
):
    """Start the explorer's Bokeh server (blocks until interrupted).

    Parameters
    ----------
    design, fluid : Design, Fluid
        The starting drive.
    architecture : str
        Idler architecture.
    port : int
        TCP port (0: any free port).
    address : str
        Address to bind (127.0.0.1 by default: this machine only).
    show : bool
        Open the page in the default browser.
    """
    from bokeh.server.server import Server

    def app(doc) -> None:
        make_document(doc, design, fluid, architecture)

    if port == 0:  # a free port, named explicitly in the allowed origins
        import socket

        with socket.socket() as sock:
            sock.bind((address, 0))
            port = sock.getsockname()[1]
    server = Server(
        {"/": app},
        port=port,
        address=address,
        allow_websocket_origin=[f"{address}:{port}", f"localhost:{port}"],
    )
    server.start()
    url = f"http://{address}:{server.port}/"
    print(f"ballcvt explorer at {url} (Ctrl-C to stop)", flush=True)
    if show:
        server.io_loop.add_callback(server.show, "/")
    try:
        server.io_loop.start()
    except KeyboardInterrupt:  # pragma: no cover - interactive
        pass
    finally:
        server.stop()
