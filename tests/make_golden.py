"""Regenerate the golden regression values: ``python tests/make_golden.py``.

Run it only when a change of the results is intended, and say why in the commit message.
"""

import json
from pathlib import Path

from ballcvt import Variator

POINTS = [("double", 0.5, 40.0), ("double", 1.0, 100.0), ("double", 1.76, 40.0),
          ("double", 2.0, 60.0), ("single", 1.0, 40.0), ("single", 0.7, 120.0)]
PATH = Path(__file__).parent / "golden" / "points.json"


def compute():
    out = []
    for arch, ratio, torque in POINTS:
        r = Variator(architecture=arch).solve(ratio=ratio, output_torque=torque,
                                              clamp_force=2000.0, input_speed_rpm=2000.0)
        out.append({"architecture": arch, "ratio": ratio, "output_torque": torque,
                    "eta": r.eta, "input_torque": r.input_torque,
                    "creep": [c.creep for c in r.contacts.values()],
                    "p_max": [c.p_max for c in r.contacts.values()],
                    "losses_total": r.losses["total"]})
    return out


if __name__ == "__main__":
    PATH.write_text(json.dumps(compute(), indent=1) + "\n")
    print(f"wrote {PATH}")
