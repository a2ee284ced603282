"""
Comparing two designs
=====================

Table I's drive against the same drive with contact angles of 40 degrees instead of 45:
efficiency against output torque at three ratios, and the limiting torques.
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator

base = Variator()
steep = Variator(base.design.replace(theta0_deg=40.0, theta2_deg=40.0))
torque = np.linspace(5.0, 150.0, 25)
fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), layout="constrained", sharey=True)
for ax, ratio in zip(axes, (0.6, 1.0, 1.6)):
    for v, label in ((base, "45 deg (Table I)"), (steep, "40 deg")):
        ds = v.sweep(ratio=[ratio], output_torque=torque, clamp_force=2000.0,
                     input_speed_rpm=2000).squeeze(drop=True)
        ax.plot(ds.output_torque, ds.eta, label=f"{label}, limit {float(ds.limit_torque):.0f} N m")
    ax.set_title(f"tau_ID = {ratio}")
    ax.set_xlabel("output torque [N m]")
    ax.legend(fontsize="small")
axes[0].set_ylabel("efficiency [-]")
plt.show()
