"""Write examples/traction/curves.csv: SYNTHETIC traction curves for `ballcvt fit-fluid`.

The curves are the thermal law's on Table I's fluid (its ASSUMED thermal constants) on a
twin-disc contact (R_x = 20 mm, R_y = 50 mm, steel), at two loads, three rolling speeds and
two spins, with Gaussian noise of standard deviation 0.0005 on mu (seed 2). They are not
measurements: they show the file layout and let the fit be checked against known values.
Run: ``python examples/traction/make_curves.py``.
"""

from pathlib import Path

import numpy as np
import pandas as pd

from ballcvt import load_builtin
from ballcvt.analysis.fitting import Curves, model_mu

design, fluid = load_builtin()
fluid = fluid.replace(traction_law="thermal")
rows = [(f"F{load:.0f}N_U{speed:g}_s{spin:g}", 0.02, 0.05, load, speed, spin, creep)
        for load in (500.0, 2500.0) for speed in (5.0, 20.0) for spin in (0.0, 0.2)
        for creep in np.geomspace(2e-4, 0.06, 12)]
frame = pd.DataFrame(rows, columns=["condition", "rx [m]", "ry [m]", "load [N]",
                                    "speed [m/s]", "spin", "creep"])
columns = [frame[c].to_numpy() for c in frame.columns]
curves = Curves(columns[0], *(np.asarray(c, dtype=float) for c in columns[1:]),
                mu=np.zeros(len(frame)))
mu = model_mu(fluid, curves, design.material.reduced_modulus)
frame["mu"] = np.round(mu + np.random.default_rng(2).normal(0.0, 5e-4, mu.size), 6)
path = Path(__file__).with_name("curves.csv")
path.write_text("# SYNTHETIC: thermal law, Table I fluid, noise 0.0005 (make_curves.py)\n"
                + frame.to_csv(index=False))
print(f"wrote {path}: {len(frame)} points, {frame['condition'].nunique()} conditions")
