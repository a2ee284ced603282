"""
Comparing the two architectures
===============================

The disassembled drive has two idlers (double); the original patent one cylindrical idler
(single). At 40 N m and 2 kN the single idler is about three points more efficient: its
idler contact spins much less (Figs. 12-13 of the paper).
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator

ratio = np.linspace(0.5, 2.0, 16)
ds = Variator().sweep(ratio=ratio, output_torque=[40.0], clamp_force=2000.0,
                      input_speed_rpm=2000, architecture=("double", "single"))
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for arch in ("double", "single"):
    one = ds.sel(architecture=arch).squeeze(drop=True)
    ax1.plot(ratio, one.eta, label=f"{arch} idler")
    ax2.semilogy(ratio, np.abs(one.creep.isel(contact=1)), label=f"{arch} idler")
ax1.set_xlabel("ideal ratio [-]")
ax1.set_ylabel("efficiency [-]")
ax2.set_xlabel("ideal ratio [-]")
ax2.set_ylabel("|creep| at the (first) idler contact [-]")
ax1.legend()
ax2.legend()
plt.show()
