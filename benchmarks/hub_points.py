"""The built-in `hub` at a rider's operating points: efficiency and loss breakdown.

At 114 rpm input, input powers 50 / 100 / 200 W and ideal ratios 0.5 / 1 / 1.8, under the
hub's loading cam. The output torque ``T_2`` of each point is the one whose solved input
power ``T_0 omega_0`` is the target power: found by the fixed point
``T_2 <- T_2 P / (T_0 omega_0)`` from ``T_2 = P tau_ID / omega_0`` (the efficiency hardly
changes with the torque, so it converges in a few steps; stopped at 1e-6 relative).

    python benchmarks/hub_points.py [--json]
"""

from __future__ import annotations

import argparse
import json
import math
import warnings

from ballcvt.api import Variator, load_builtin

SPEED_RPM = 114.0
POWERS = (50.0, 100.0, 200.0)
RATIOS = (0.5, 1.0, 1.8)


def point(v: Variator, ratio: float, power: float) -> dict:
    """The point of input power ``power`` [W] at ``ratio``: efficiency and losses [W]."""
    w0 = SPEED_RPM * math.pi / 30.0
    t2 = power * ratio / w0
    for _ in range(30):
        r = v.solve(ratio, t2, clamp_law="cam", input_speed_rpm=SPEED_RPM)
        p_in = r.input_torque * w0
        if abs(p_in - power) < 1e-6 * power:
            break
        t2 *= power / p_in
    losses = {k: round(float(x), 4) for k, x in r.losses.items()}
    return {
        "ratio": ratio,
        "input_power": round(float(p_in), 4),
        "output_torque": round(float(t2), 4),
        "clamp_force": round(float(r.clamp_force), 2),
        "eta": round(float(r.eta), 5),
        "losses": losses,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    warnings.simplefilter("ignore")
    v = Variator(*load_builtin("hub"))
    rows = [point(v, ratio, p) for p in POWERS for ratio in RATIOS]
    if args.json:
        print(json.dumps(rows, indent=1))
        return
    for row in rows:
        parts = ", ".join(f"{k} {x:.3f}" for k, x in row["losses"].items() if x)
        print(
            f"P {row['input_power']:6.1f} W  ratio {row['ratio']:.1f}  T2 {row['output_torque']:6.2f}"
            f"  F_N0 {row['clamp_force']:7.1f}  eta {row['eta']:.4f}  [{parts}]"
        )


if __name__ == "__main__":
    main()
