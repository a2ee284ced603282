"""Make the example duty cycles of ballcvt (run: ``python examples/cycles/make_cycles.py``).

Both files are data made by this script, deterministic, and committed; nothing is fetched.

* ``ebike_commute.csv`` (output side): a 20-minute e-bike commute sampled every second.
  The rear-hub output is the wheel. Its torque is the road load on a 100 kg rider and bike
  (rolling resistance 0.006, CdA 0.5 m^2, air 1.2 kg/m^3, wheel radius 0.35 m):
  ``T_2 = r (m dv/dt + m g (C_rr cos(a) + sin(a)) + rho CdA v^2 / 2)``. The route has
  two traffic stops, a 4 % climb at 15 km/h and a 5 % descent where the rider brakes
  (negative torque: outside the model, flagged by the runner). The bike's speed is a
  column too (``vehicle_speed``: the commute's distance, a fatigue life in km).
* ``rig_power_ramp.csv`` (input side): a test-rig ramp at 2000 rpm input and a constant
  5 kW input power while the commanded ratio sweeps 0.5 -> 2 in 120 s (2 samples/s).
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).parent
MASS, CRR, CDA, RHO_AIR, G, WHEEL = 100.0, 0.006, 0.5, 1.2, 9.81, 0.35


def commute():
    """(time [s], wheel speed [rpm], wheel torque [N m], bike speed [km/h]) of the commute."""
    # (duration [s], speed at the end [km/h], grade [-]); speeds ramp linearly
    legs = [(20, 25, 0.0), (220, 25, 0.0), (15, 0, 0.0), (30, 0, 0.0),      # stop 1
            (20, 25, 0.0), (100, 25, 0.0), (20, 15, 0.04), (180, 15, 0.04),  # climb
            (30, 30, -0.05), (60, 30, -0.05), (20, 25, 0.0), (200, 25, 0.0),
            (15, 0, 0.0), (45, 0, 0.0),                                      # stop 2
            (20, 25, 0.0), (165, 25, 0.0), (20, 0, 0.0), (20, 0, 0.0)]
    t_end = np.cumsum([d for d, _, _ in legs])
    v_end = np.array([v for _, v, _ in legs]) / 3.6
    grade = np.array([g for _, _, g in legs])
    t = np.arange(0.0, t_end[-1] + 1.0)
    v = np.interp(t, np.concatenate([[0.0], t_end]), np.concatenate([[0.0], v_end]))
    leg = np.minimum(np.searchsorted(t_end, t, side="left"), len(legs) - 1)
    slope = np.arctan(grade[leg])
    accel = np.gradient(v, t)
    force = (MASS * accel + MASS * G * (CRR * np.cos(slope) + np.sin(slope))
             + 0.5 * RHO_AIR * CDA * v**2)
    force = np.where(v > 0, force, 0.0)            # standing still: no drive torque
    return t, v / WHEEL * 30.0 / np.pi, force * WHEEL, v * 3.6


def rig():
    t = np.arange(0.0, 120.5, 0.5)
    return t, np.full(t.size, 2000.0), np.full(t.size, 5000.0), np.linspace(0.5, 2.0, t.size)


def write(path, header, columns, note):
    rows = np.column_stack(columns)
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {note}\n# made by examples/cycles/make_cycles.py\n")
        f.write(",".join(header) + "\n")
        for row in rows:
            f.write(",".join(f"{x:.6g}" for x in row) + "\n")
    print(f"wrote {path} ({len(rows)} steps)")


if __name__ == "__main__":
    write(HERE / "ebike_commute.csv",
          ["time [s]", "output_speed [rpm]", "output_torque [N m]", "vehicle_speed [km/h]"],
          commute(), "e-bike commute, rear hub output = wheel (see make_cycles.py)")
    write(HERE / "rig_power_ramp.csv",
          ["time [s]", "input_speed [rpm]", "input_power [W]", "ratio [1]"], rig(),
          "test rig: 2000 rpm, 5 kW input, ratio ramp 0.5 -> 2")
