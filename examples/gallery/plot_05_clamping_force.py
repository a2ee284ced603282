"""
Picking a clamping force
========================

Too little clamping and the contacts creep towards the traction limit; too much and the
spin and bearing losses grow with the load. The efficiency-optimal force (docs/model.md §9)
is the smallest that keeps the creep and the peak pressure within their limits.
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator

v = Variator()
forces = np.linspace(600.0, 4000.0, 18)
fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
for torque in (20.0, 40.0, 80.0):
    ds = v.sweep(ratio=[1.0], output_torque=[torque], clamp_force=forces,
                 input_speed_rpm=2000).squeeze(drop=True)
    (line,) = ax.plot(forces, ds.eta, label=f"{torque:g} N m")
    best = v.optimal_clamp_force(1.0, torque, input_speed_rpm=2000)
    ax.plot(best.clamp_force, best.eta, "o", color=line.get_color())
ax.set_xlabel("clamping force F_N0 [N]")
ax.set_ylabel("efficiency [-]")
ax.set_title("tau_ID = 1, 2000 rpm; dots: the optimal force")
ax.legend()
plt.show()
