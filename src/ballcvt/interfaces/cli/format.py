"""Plain-text tables for the command line."""

from __future__ import annotations

from ...api import OperatingResult, PlanetaryResult
from ...units import kelvin_to_celsius, rad_s_to_rpm

__all__ = ["point_table", "planetary_table", "limit_table", "clamp_table"]

_ROWS = [  # (label, attribute, unit, scale, format)
    ("creep C", "creep", "-", 1.0, "{:+.4e}"),
    ("spin sigma", "spin", "-", 1.0, "{:+.4f}"),
    ("traction mu", "mu", "-", 1.0, "{:+.4e}"),
    ("spin moment chi", "chi", "-", 1.0, "{:+.4e}"),
    ("normal load", "normal_load", "N", 1.0, "{:.1f}"),
    ("peak pressure", "p_max", "GPa", 1e-9, "{:.3f}"),
    ("semi-axis a_x", "semi_axis_x", "mm", 1e3, "{:.4f}"),
    ("semi-axis a_y", "semi_axis_y", "mm", 1e3, "{:.4f}"),
    ("film thickness", "film_thickness", "um", 1e6, "{:.4f}"),
    ("film ratio h_min/sigma", "lambda_ratio", "-", 1.0, "{:.2f}"),
    ("creep loss", "creep_loss", "W", 1.0, "{:.2f}"),
    ("spin loss", "spin_loss", "W", 1.0, "{:.2f}"),
]
#: Rows shown under a mixed lubrication model (docs/model.md §16).
_MIXED_ROWS = [
    ("film param. h/sigma", "film_parameter", "-", 1.0, "{:.2f}"),
    ("asperity load share", "asperity_fraction", "%", 100.0, "{:.3f}"),
]


def point_table(r: OperatingResult, efficiency: str = "") -> str:
    """Readable summary of an operating point; ``efficiency`` replaces its efficiency
    line (a planetary point's carrier frame, by the way its power flows)."""
    names = list(r.contacts)
    w = 12
    lines = [
        f"ballcvt {r.version}  {r.architecture} idler  ({r.design.name})",
        f"ratio tau_ID {r.ratio:.4g}   tilt {r.tilt_deg:+.3f} deg   actual ratio "
        f"{r.actual_ratio:.5f}",
        f"input  {r.input_speed_rpm:8.1f} rpm  {r.input_torque:9.3f} N m  "
        f"{r.input_power / 1e3:8.3f} kW",
        f"output {rad_s_to_rpm(r.output_speed):8.1f} rpm  {r.output_torque:9.3f} N m  "
        f"{r.output_power / 1e3:8.3f} kW",
        f"clamp F_N0 {r.clamp_force:.1f} N ({r.clamp_law} law), disc thrust "
        f"{r.axial_force:.1f} N, {r.traction_law} traction law",
        "",
        f"{'contact':<22}" + "".join(f"{n:>{w}}" for n in names),
    ]
    lub = r.design.lubrication
    mixed = lub is not None and lub.model != "full-film"
    for label, attr, unit, scale, fmt in _ROWS + (_MIXED_ROWS if mixed else []):
        cells = "".join(f"{fmt.format(getattr(r.contacts[n], attr) * scale):>{w}}" for n in names)
        lines.append(f"{label + ' [' + unit + ']':<22}{cells}")
    ls = r.losses
    lines += [
        "",
        f"losses [W]  creep {ls['creep']:.2f}  spin {ls['spin']:.2f}  bearings "
        f"{ls['roller_bearings'] + ls['idler_bearings']:.2f}"
        + (
            f"  churning {ls['churning']:.2f}  seals {ls['seals']:.2f}"
            f"  disc bearings {ls['disc_bearings']:.2f}"
            if any(ls.get(k) for k in ("churning", "seals", "disc_bearings"))
            else ""
        )
        + (f"  hub bearings {ls['hub_bearings']:.2f}" if ls.get("hub_bearings") else "")
        + f"  total {ls['total']:.2f}",
        efficiency
        or f"efficiency  overall {r.eta:.5f} (Eq. 38)  {r.eta_loss:.5f} (Eq. 39)  "
        f"speed {r.eta_speed:.5f}  torque {r.eta_torque:.5f}",
        f"solver      {'converged' if r.converged else 'NOT CONVERGED'}, max|residual| "
        f"{r.residual_norm:.1e}, {r.iterations} evaluations, quadrature {r.quadrature}",
    ]
    if r.oil_model != "fixed" and r.oil_temperature is not None:
        how = f", {r.thermal_iterations} points solved" if r.oil_model == "balance" else ""
        lines.append(
            f"oil         {kelvin_to_celsius(r.oil_temperature):.2f} C ({r.oil_model}{how}), "
            f"eta_0 {r.fluid.viscosity * 1e3:.4g} mPa s"
        )
    lines += [f"warning: {w}" for w in r.warnings] or ["validity    no warnings"]
    return "\n".join(lines)


def limit_table(data: dict) -> str:
    """Readable limiting-torque line."""
    clamp = (
        f"F_N0 {data['clamp_force']:g} N"
        if data["clamp_law"] == "constant"
        else f"{data['clamp_law']} clamping law"
    )
    mode = data.get("mode")
    what = (
        "limiting output torque"
        if mode is None
        else f"limiting load torque of the {mode['driven']} ({mode['label']})"
    )
    spans = data.get("capacity_intervals") or [[0.0, data["limit_torque"]]]
    head = (
        f"{what} {data['limit_torque']:.2f} N m"
        if len(spans) == 1 and spans[0][0] == 0.0
        else "admissible output torques "
        + " or ".join(f"{lo:.2f} to {hi:.2f} N m" for lo, hi in spans)
    )
    return (
        f"{head}  ({data['architecture']} "
        f"idler, ratio {data['ratio']:g}, {clamp}, "
        f"{data['input_speed_rpm']:g} rpm{'' if mode is None else ' driver'}, "
        f"|creep| <= {data['creep_limit']:g})"
        + (f"\n  set by: {data['active_constraint']}" if data.get("active_constraint") else "")
        + _interval_ends(spans, data.get("interval_constraints"))
    )


def _interval_ends(spans, ends) -> str:
    """What sets each end, when the admissible torques do not simply run from zero."""
    if not ends or (len(spans) == 1 and spans[0][0] == 0.0):
        return ""
    return "".join(
        f"\n  {lo:.2f} N m set by {a}, {hi:.2f} N m set by {b}"
        for (lo, hi), (a, b) in zip(spans, ends)
    )


def clamp_table(data: dict) -> str:
    """Readable optimal-clamping-force summary."""
    lo, hi = data["feasible_clamp_range"]
    return (
        f"optimal clamping force {data['clamp_force']:.0f} N: eta {data['eta']:.5f}, "
        f"max |creep| {data['max_creep']:.4f}, max p_max {data['max_pressure'] / 1e9:.3f} "
        f"GPa\n  ({data['architecture']} idler, ratio {data['ratio']:g}, T2 "
        f"{data['output_torque']:g} N m, {data['input_speed_rpm']:g} rpm; feasible "
        f"F_N0 {lo:.0f}-{hi:.0f} N, active constraint: {data['active_constraint']})"
    )


def planetary_table(r: PlanetaryResult) -> str:
    """Readable summary of an operating point in a planetary mode: the members, then the
    carrier-frame point."""
    m = r.mode
    lines = [
        f"planetary mode: {m.label}"
        + (
            ""
            if m.centrifugal and m.gyroscopic
            else "  (without "
            + " and ".join(
                n
                for n, on in (
                    ("centrifugal force", m.centrifugal),
                    ("gyroscopic moment", m.gyroscopic),
                )
                if not on
            )
            + ")"
        ),
        f"{'member':<10}{'speed [rpm]':>14}{'torque [N m]':>14}{'power [kW]':>12}",
    ]
    for name in ("disc0", "disc2", "carrier"):
        tag = {
            m.held: " held" if m.held_speed == 0.0 else " given",
            m.driver: " driver",
            m.driven: " driven",
        }[name]
        lines.append(
            f"{name + tag:<16}{rad_s_to_rpm(r.speeds[name]):8.1f}{r.torques[name]:14.3f}"
            f"{r.powers[name] / 1e3:12.4f}"
        )
    lines += [
        f"overall ratio (driven / driver) {r.overall_ratio:+.5f}   torque ratio "
        f"{r.torque_ratio:+.4f}",
        (
            f"efficiency  power out / power in {r.eta:.5f}   1 - losses / power in "
            f"{r.eta_loss:.5f}   (in through {r.input_member}, out through "
            f"{r.output_member})"
            if not r.geared_neutral
            else "geared neutral: the driven member is at rest, so the efficiency says nothing; "
            f"read the torque ratio ({r.torque_ratio:+.4f})"
        ),
        f"power flow  {r.power_flow}; through the contacts {r.circulating_power / 1e3:.4f} kW"
        f" (shaft power {abs(r.input_power) / 1e3:.4f} kW)",
        "",
        "in the carrier frame"
        + (" (mirrored: speeds and torques negated)" if r.sign < 0 else "")
        + ":",
        point_table(r.relative, _variator_line(r)),
    ]
    return "\n".join(lines)


def _variator_line(r: PlanetaryResult) -> str:
    """The carrier-frame efficiency line of a planetary point, by its power flow."""
    var = r.variator_efficiency
    return (
        f"efficiency  variator {var['eta']:.5f} ({r.power_flow.split(' (')[0]})  "
        f"speed {var['speed']:.5f}  torque {var['torque']:.5f}"
    )
