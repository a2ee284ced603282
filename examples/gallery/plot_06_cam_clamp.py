"""
A self-clamping drive: the loading cam
======================================

The paper's rig clamps with a constant 2 kN. A hub clamps itself: a ball-ramp cam on the
output disc turns the output torque into axial force, so the clamp follows the load
(docs/model.md §11). The built-in drive ``hub`` has such a cam (1 kN preload, 6 deg ramp
at 50 mm, ASSUMED). Here: efficiency and clamping force against output torque at ratio 1,
the cam against the constant 2 kN, and the limiting torque of each.
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator, load_builtin
from ballcvt.api import with_oil_temperature

# The hub's drive file runs its oil at the heat balance of its shell. Here the oil is held
# at the fluid's 40 C, as on the paper's rig: at 2000 rpm the constant 2 kN spins away
# ~1.4 kW, more than the hub's shell can reject (the balance refuses it as a runaway).
design, fluid = load_builtin("hub")
hub = with_oil_temperature(Variator(design, fluid), "fixed")
print(design.cam)

torque = np.linspace(5.0, 200.0, 14)
laws = {"constant 2 kN": {"clamp_force": 2000.0}, "cam": {"clamp_law": "cam"}}
runs = {label: hub.sweep(ratio=[1.0], output_torque=torque, input_speed_rpm=2000,
                         progress=False, **law) for label, law in laws.items()}

# %%
# Beyond its limiting torque a point has status 1 and NaN efficiency: the lines stop
# there instead of inventing a value. Where the clamp is constant the limit is set by the
# creep; the cam raises the clamp with the torque and carries far more, until the peak
# pressure reaches ``design.max_pressure``.

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for label, ds in runs.items():
    one = ds.squeeze(drop=True)
    limit = float(np.max(one.limit_torque))
    (line,) = ax1.plot(torque, one.eta, "o-", ms=3, label=f"{label} (limit {limit:.0f} N m)")
    # the cam's force is a result (a variable); the constant force is a sweep coordinate
    force = one["clamp_force"] if "clamp_force" in one.data_vars else 2000.0 + 0 * one.eta
    ax2.plot(torque, force.where(one.status == 0) / 1e3, "o-", ms=3,
             color=line.get_color(), label=label)
    at40 = hub.solve(ratio=1.0, output_torque=40.0, input_speed_rpm=2000, **laws[label])
    print(f"{label}: limiting torque {limit:.0f} N m; at 40 N m eta = {at40.eta:.3f} "
          f"with F_N0 = {at40.clamp_force:.0f} N")
ax1.set_xlabel("output torque [N m]")
ax1.set_ylabel("efficiency [-]")
ax1.set_title("hub drive, tau_ID = 1, 2000 rpm")
ax2.set_xlabel("output torque [N m]")
ax2.set_ylabel("clamping force F_N0 [kN]")
ax2.set_title("the cam's force follows the torque")
ax1.legend(fontsize="small")
ax2.legend(fontsize="small")
plt.show()
