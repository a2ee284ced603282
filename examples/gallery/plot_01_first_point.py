"""
First point, and what each number means
=======================================

One operating point of the paper's Table I drive: ideal ratio 1.76, 40 N m out, a
clamping force of 2 kN at each input contact, 2000 rpm in. `Variator.solve` finds the
creeps at which every ball, idler and disc is in equilibrium (docs/model.md §5), and from
them everything else.
"""

import matplotlib.pyplot as plt

from ballcvt import Variator

v = Variator()
r = v.solve(ratio=1.76, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000)
print(r)

# %%
# * **ideal ratio** ``tau_ID`` sets the ball tilt (Eq. 4); the **actual ratio** is lower by
#   the creeps (Eq. 8), and its shortfall is the speed efficiency (Eq. 9).
# * **efficiency** (Eq. 38) is output over input power; Eq. 39, one minus the losses over
#   the input power, gives the same number (``r.eta_loss``).
# * the **losses** split into creep (sliding in the rolling direction), spin (the
#   contacts' rotation about their normals, the largest here) and bearings.
# * per contact: **creep** (Eq. 7), **spin** (Eqs. 11-14), traction ``mu`` and spin-moment
#   ``chi`` coefficients (Eqs. 30-31), Hertz peak pressure, film thickness (Eq. 56).

contacts = r.to_dataframe()
print(contacts[["creep", "spin", "mu", "p_max", "film_thickness"]])

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
kinds = ["creep", "spin", "roller_bearings", "idler_bearings"]
ax1.bar(kinds, [r.losses[k] for k in kinds])
ax1.set_ylabel("power loss [W]")
ax1.set_title(f"losses at eta = {r.eta:.3f} ({r.input_power / 1e3:.1f} kW in)")
ax2.bar(contacts.index, contacts["p_max"] / 1e9)
ax2.set_ylabel("Hertz peak pressure [GPa]")
ax2.set_title("peak pressure per contact")
plt.show()
