"""
Comparing the two architectures
===============================

The disassembled drive has two idlers (double); the original patent one cylindrical idler
(single). At 40 N m and 2 kN the single idler is up to about two points more efficient
near ratio 1, where its one idler contact hardly spins; towards the ends of the range its
idler spin loss exceeds the double idler's and the two meet (Figs. 12-13 of the paper).
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator

ratio = np.linspace(0.5, 2.0, 16)
ds = Variator().sweep(ratio=ratio, output_torque=[40.0], clamp_force=2000.0,
                      input_speed_rpm=2000, architecture=("double", "single"))
print(ds.contact.values)

# %%
# A sweep over both architectures has the union of their contacts: ``input``, ``idler``
# (the single idler's one contact), ``idler_a`` and ``idler_b`` (the double idler's two),
# ``output``. Each architecture's values are NaN at the other's idler contacts, so select
# the idler contacts by name for each architecture (``isel(contact=1)`` would pick
# ``idler``: all NaN for the double idler).

IDLER_CONTACTS = {"double": ["idler_a", "idler_b"], "single": ["idler"]}
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
for arch in ("double", "single"):
    one = ds.sel(architecture=arch).squeeze(drop=True)
    idler = one.spin_loss.sel(contact=IDLER_CONTACTS[arch]).sum("contact")
    ax1.plot(ratio, one.eta, label=f"{arch} idler")
    ax2.plot(ratio, idler, label=f"{arch} idler ({' + '.join(IDLER_CONTACTS[arch])})")
ax1.set_xlabel("ideal ratio [-]")
ax1.set_ylabel("efficiency [-]")
ax2.set_xlabel("ideal ratio [-]")
ax2.set_ylabel("spin loss at the idler contacts [W]")
ax1.legend()
ax2.legend()
plt.show()
