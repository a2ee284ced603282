"""
How long does a 0.5 -> 1.8 shift take, and how hard is it?
==========================================================

A skew-steered hub shifts by skewing the balls' axles a little: the contacts then steer
every ball to a new tilt at ``d(gamma)/dt = omega_b cos(gamma) tan(zeta)``, the rate at
which no contact slips sideways (docs/shifting.md). The ball's speed ``omega_b`` follows
the input, so the shift takes half as long at twice the cadence, whatever the load. Here:
the hub from 0.5 to 1.8 with a 1 degree skew, at 60 and 90 rpm cadence (x 38/20 at the
hub's sprocket), under 20 and 60 N m.

How hard it is: a tilt-direct hub (the rider's shifter tilts the axles) shifting as fast,
at the skew shift's mean tilt rate, must overcome the holding moment and the side forces
of the side slip it imposes. Those moments come from the contact model,
``Variator.shift_moments``; with a build that has none, the moment panel says so (the
moments are never made up) and the times and efficiencies are still drawn.
"""

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator, load_builtin

hub = Variator(*load_builtin("hub"))
fig, (top, middle, bottom) = plt.subplots(3, 1, figsize=(6.5, 8.0), sharex=True,
                                          layout="constrained")
for cadence, style in ((60, "-"), (90, "--")):
    for torque, color in ((20.0, "tab:blue"), (60.0, "tab:red")):
        point = {"clamp_law": "cam", "input_speed_rpm": cadence * 38 / 20, "samples": 31}
        skew = hub.shift(0.5, 1.8, torque, skew_deg=1.0, **point)
        s = skew.samples
        # tilt-direct at the skew shift's mean tilt rate: the same shift time
        rate = (s.tilt_deg.iloc[-1] - s.tilt_deg.iloc[0]) / skew.shift_time_s
        direct = hub.shift(0.5, 1.8, torque, tilt_rate_deg_s=rate, **point)
        label = f"{cadence} rpm cadence, {torque:g} N m"
        print(f"{label}: {skew.shift_time_s:.3f} s, losses {skew.loss_energy_J:.1f} J; "
              f"tilt-direct at {rate:.0f} deg/s: peak moment "
              f"{direct.peak_shift_moment_Nm:.3g} N m")
        top.plot(s.time_s, s.ratio, style, color=color, label=label)
        moment = direct.samples.shifter_moment_Nm.to_numpy()
        if np.isfinite(moment).any():
            middle.plot(direct.samples.time_s, moment, style, color=color, label=label)
        bottom.plot(s.time_s, s.eta, style, color=color, label=label)
top.set_ylabel(r"ideal ratio $\tau_{ID}$ [-]")
top.legend(fontsize=8)
middle.set_ylabel("tilt-direct shifter\nmoment [N m]")
if middle.get_lines():
    middle.legend(fontsize=8)
else:
    middle.text(0.5, 0.5, "no shift-moment model in this build", ha="center", va="center",
                transform=middle.transAxes, color="tab:gray")
bottom.set_ylabel(r"efficiency $\eta$ [-]")
bottom.set_xlabel("time [s]")
fig.suptitle("hub, cam clamping: 0.5 -> 1.8 with a 1 deg skew")
plt.show()
