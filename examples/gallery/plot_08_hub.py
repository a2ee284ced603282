"""
The drive as built: the ``hub``
===============================

The built-in drive ``hub`` is the paper's Table I drive as a bicycle hub would be built:
the same balls, discs and fluid, plus a loading cam on the output disc and the parasitic
losses of a real housing (oil churning, two lip seals, a thrust bearing between the
discs; every value ASSUMED and sized in docs/model.md §11-12). Export it with
``ballcvt design export my_hub.toml --design hub`` to edit it.

Here: where its power goes at one point, and its efficiency map under its own cam and
its oil's heat balance.
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator, load_builtin
from ballcvt.plotting import plot_efficiency_map

design, fluid = load_builtin("hub")
hub = Variator(design, fluid)
print(design.name)
r = hub.solve(ratio=1.0, output_torque=30.0, clamp_law="cam", input_speed_rpm=180)
print(r)

# %%
# At a cyclist's 30 N m and 180 rpm in, the cam clamps lightly, the contacts lose little,
# and the parasitic terms (which do not depend on the load) are a visible share of the
# loss: ``r.losses`` holds every component in watts and one ``total``, their sum (left out
# of the bars).

kinds = [k for k in r.losses if k != "total"]
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
ax1.barh(kinds, [r.losses[k] for k in kinds])
ax1.set_xlabel("power loss [W]")
ax1.set_title(f"30 N m, 180 rpm in: eta = {r.eta:.3f}, F_N0 = {r.clamp_force:.0f} N (cam)")

# %%
# The map runs every point at its own oil temperature: the hub's drive file names the heat
# balance of its shell (``[models] oil_temperature = "balance"``, docs/model.md §15). Its
# limit line is not the cam's pressure limit (383 N m with a 40 C oil) but where the shell
# can no longer reject the losses in steady running: above it the oil runs away (status 2),
# from about 220 N m at ratio 0.5 to about 110 N m at ratio 2.

ds = hub.sweep(ratio=np.linspace(0.5, 2.0, 5), output_torque=np.linspace(10.0, 290.0, 6),
               clamp_law="cam", input_speed_rpm=180, progress=False)
print(ds["limit_torque"].squeeze().round(1).values)
plot_efficiency_map(ds, ax=ax2)
plt.show()
