"""How each clamping law changes the Fig. 8 picture (docs/cycles.md).

Efficiency against output torque at tau_ID = 1 and 2000 rpm on the Table I drive: the
paper's constant clamping forces, the loading cam of the built-in ``hub`` drive (whose
cam is sized in docs/model.md §11), and the efficiency-optimal force. Prints the table of
docs/cycles.md and writes ``clamping_laws.png``.

Run: ``python examples/clamping_laws.py``
"""

import numpy as np
from matplotlib.figure import Figure

from ballcvt import Variator

v = Variator()                       # Table I; its file carries the example cam
TORQUES = [10.0, 40.0, 80.0, 150.0, 300.0]
SPEED = {"input_speed_rpm": 2000.0}


def eta(torque, **law):
    try:
        r = v.solve(1.0, torque, **law, **SPEED)
    except Exception:                # beyond this law's capacity
        return float("nan"), float("nan")
    return r.eta, r.clamp_force


print("| output torque | eta, constant 2 kN | eta, cam | F_N0 of the cam | eta, optimal | "
      "F_N0, optimal |")
print("|---|---|---|---|---|---|")
for t in TORQUES:
    c, _ = eta(t, clamp_force=2000.0)
    cam, f_cam = eta(t, clamp_law="cam")
    opt, f_opt = eta(t, clamp_law="optimal")
    cell = lambda x, fmt: "beyond capacity" if np.isnan(x) else fmt.format(x)  # noqa: E731
    print(f"| {t:g} N m | {cell(c, '{:.4f}')} | {cell(cam, '{:.4f}')} | "
          f"{cell(f_cam, '{:.0f} N')} | {cell(opt, '{:.4f}')} | {cell(f_opt, '{:.0f} N')} |")

fig = Figure(figsize=(7, 4.5), layout="constrained")
ax = fig.subplots()
for force in (1000.0, 2000.0, 3000.0):
    ds = v.sweep(ratio=1.0, output_torque=np.linspace(2, 380, 60), clamp_force=force,
                 progress=False, **SPEED)
    ax.plot(ds.output_torque, ds.eta.squeeze(), lw=1, label=f"constant {force:g} N")
for law, style in (("cam", "k-"), ("optimal", "k--")):
    torque = (np.linspace(2, 380, 40) if law == "cam" else
              np.array([2, 5, 10, 20, 35, 50, 75, 100, 150, 200, 250, 300, 380.0]))
    ds = v.sweep(ratio=1.0, output_torque=torque, clamp_law=law, progress=False, **SPEED)
    ax.plot(ds.output_torque, ds.eta.squeeze(), style, lw=2, label=law)
ax.set_xlabel("output torque $T_2$ [N m]")
ax.set_ylabel(r"overall efficiency $\eta$ [-]")
ax.set_title(r"Clamping laws, Table I drive, $\tau_{ID}$ = 1, 2000 rpm")
ax.legend()
fig.savefig("clamping_laws.png", dpi=120)
print("wrote clamping_laws.png")
