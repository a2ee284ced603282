"""
Your first hour with ballcvt
============================

A tutorial from nothing to a result you can defend: a design, one operating point with
every number of its printout explained, a sweep, a plot, and one change to the design's
operation and why it matters. It runs when the documentation is built, so every number
below is the one the code gives today. The model behind it: :doc:`../model`.
"""

# %%
# 1. A design
# -----------
# ``Variator()`` is the drive of the paper's Table I: eight 30 mm steel balls between an
# input and an output disc, two idlers (the "double" architecture), and the paper's
# traction fluid. Printing it shows what you are computing with.

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator

v = Variator()
print(v)

# %%
# * **rollers** ``8 x r_S 30 mm``: the number of balls and their radius :math:`r_S`.
# * **aspect ratio k** :math:`k = r_1/r_S`: the idler's radius in ball radii; the ball
#   centres sit at :math:`(1 + k)\,r_S` from the main axis, which sets the rolling radii
#   of every contact (docs/model.md §1, with a labelled figure).
# * **contact angles** :math:`\theta_0 / \theta_2`: where the input and output discs
#   touch the ball (45 deg each).
# * **ratio range**: the ideal speed ratios reachable within the tilt's safety factor
#   (0.8 of the geometric limit, Eq. 6). Outside it ``solve`` refuses in one line.
# * **traction law** and **quadrature**: how the shear stress in each contact is modelled
#   (Appendix A of the paper: isothermal, as the paper) and integrated over the contact
#   ellipse (32 x 24 nodes, within about 3e-5 in efficiency of a much finer rule;
#   docs/model.md §3).
#
# 2. One operating point
# ----------------------
# An operating point is four numbers: the ideal ratio (which sets the balls' tilt), the
# output torque the load asks for, the clamping force pressing the discs onto the balls
# (the paper's :math:`F_{N0}`, at each input contact) and the input speed.

r = v.solve(ratio=1.76, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000)
print(r)

# %%
# Line by line:
#
# * **ideal ratio tau_ID** 1.76: output over input speed if nothing slipped (Eq. 4).
# * **actual ratio**: lower, because every contact creeps a little (Eq. 8). Its ratio to
#   the ideal one is the *speed efficiency* ``r.eta_speed``.
# * **tilt**: the ball's spin axis angle :math:`\gamma` that gives this ideal ratio.
# * **input speed**, **output torque T_2**: what you asked for.
# * **input torque T_0**: what the input must supply. Without losses it would be
#   :math:`\tau_{ID} T_2` (70.4 N m here: the output turns 1.76 times faster, so the input
#   torque is 1.76 times larger); :math:`\tau_{ID} T_2 / T_0` is the *torque efficiency*
#   ``r.eta_torque`` (Eq. 37).
# * **input power**: :math:`T_0\,\omega_0`.
# * **efficiency (Eq. 38)**: output over input power, ``r.eta`` = ``eta_speed *
#   eta_torque``. Eq. 39 (one minus losses over input power, ``r.eta_loss``) agrees.
# * **losses** and their split: **creep** (sliding along the rolling direction, grows with
#   the torque), **spin** (the contact patches twisting about their normals, grows with
#   the clamping load; the largest here), **bearings** (the balls' and idlers' bearings).
# * **max |creep|**: the largest creep of any contact; the drive's capacity ends where it
#   reaches ``design.creep_limit`` (0.1).
# * **max p_max**: the highest Hertz peak pressure (1.63 GPa at 2 kN, as the paper).
# * **min film**: the thinnest lubricant film; here 0.50 um against a composite roughness
#   of 0.07 um (``design.surface_roughness``): a full film, no mixed-lubrication warning.
# * **clamp F_N0**: the force used, and the law that set it (here: the constant you gave).
# * **converged**, **residual**: the equilibrium of balls, idlers and discs was found to
#   that accuracy; **warnings** count model-validity warnings (e.g. a thin film).
#
# Per contact, ``r.to_dataframe()`` has the creep, spin, traction coefficient, pressure,
# film and losses:

print(r.to_dataframe()[["creep", "spin", "mu", "p_max", "spin_loss"]])

# %%
# 3. A sweep
# ----------
# ``sweep`` solves a grid of points (here one ratio, 16 torques) and returns an
# ``xarray.Dataset``. Points beyond the drive's limiting torque are not solved: their
# ``status`` is 1 and their values NaN, and ``limit_torque`` says where the limit is.

torque = np.linspace(5.0, 150.0, 16)
base = v.sweep(ratio=[1.76], output_torque=torque, clamp_force=2000.0,
               input_speed_rpm=2000, progress=False).squeeze(drop=True)
print(f"limiting torque at 2 kN: {float(base.limit_torque):.1f} N m; "
      f"{int((base.status == 1).sum())} of {torque.size} points beyond it")

# %%
# 4. One change: clamp with 1 kN instead of 2 kN
# ----------------------------------------------
# The clamping force is the first thing to choose in a real drive. Halve it at the same
# point:

light = v.solve(ratio=1.76, output_torque=40.0, clamp_force=1000.0, input_speed_rpm=2000)
print(f"eta {r.eta:.3f} -> {light.eta:.3f}; spin loss {r.losses['spin']:.0f} W -> "
      f"{light.losses['spin']:.0f} W; creep loss {r.losses['creep']:.0f} W -> "
      f"{light.losses['creep']:.0f} W")
half = v.sweep(ratio=[1.76], output_torque=torque, clamp_force=1000.0,
               input_speed_rpm=2000, progress=False).squeeze(drop=True)
print(f"limiting torque at 1 kN: {float(half.limit_torque):.1f} N m")

# %%
# Why it matters: at 40 N m the 2 kN drive is over-clamped. The spin loss follows the
# load, so halving the clamp cuts it by about four fifths and the efficiency gains three
# points, while the creep (which must now carry the same torque with half the normal
# force) roughly doubles. But the capacity halves too: 40 N m is now close to the new
# limit, with no margin for a torque peak. The plot shows both: the light clamp is better
# at light load and stops where the heavy one carries on. A clamp that follows the
# torque (a cam, :doc:`plot_06_cam_clamp`) gets both.
#
# 5. A plot
# ---------

fig, ax = plt.subplots(figsize=(6.5, 4.2), layout="constrained")
for ds, label in ((base, "2 kN"), (half, "1 kN")):
    (line,) = ax.plot(ds.output_torque, ds.eta, "o-", ms=3,
                      label=f"{label}, limit {float(ds.limit_torque):.0f} N m")
    ax.axvline(float(ds.limit_torque), color=line.get_color(), ls=":", lw=1)
ax.set_xlabel("output torque T_2 [N m]")
ax.set_ylabel("efficiency [-]")
ax.set_title("Table I drive, tau_ID = 1.76, 2000 rpm; dotted: limiting torque")
ax.legend()
plt.show()
