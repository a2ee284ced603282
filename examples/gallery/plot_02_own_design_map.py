"""
An efficiency map of your own design, from TOML
===============================================

Export the Table I drive as TOML (with its sources), change it, and load it back: the file
is validated, and a design that cannot be built is refused with the reason (nine 25 mm
balls do not fit at Table I's aspect ratio: the carrier circle must grow). Here the balls
are made smaller (25 mm), the aspect ratio larger (2.0), and one ball is added.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from ballcvt import Variator
from ballcvt.params.io import builtin_text, load_drive
from ballcvt.plotting import plot_efficiency_map

text = builtin_text("table1")
text = text.replace("roller_radius = 0.03 ", "roller_radius = 0.025 ")
text = text.replace("n_rollers = 8 ", "n_rollers = 9 ")
text = text.replace("aspect_ratio = 1.7 ", "aspect_ratio = 2.0 ")
path = Path(tempfile.mkdtemp()) / "my_drive.toml"
path.write_text(text)
design, fluid = load_drive(path)
v = Variator(design, fluid)
print(v)

ds = v.sweep(
    ratio=np.linspace(0.5, 2.0, 13),
    output_torque=np.linspace(5.0, 120.0, 16),
    clamp_force=2000.0,
    input_speed_rpm=2000,
)
fig, ax = plt.subplots(figsize=(6.5, 4.6), layout="constrained")
plot_efficiency_map(ds, ax=ax)
ax.set_title(f"{design.n_rollers} balls of {design.roller_radius * 1e3:g} mm, 2 kN, 2000 rpm")
plt.show()
