"""
How long does the hub last on the commute?
==========================================

Every track of the drive (the two discs, the idlers, each ball's tracks) and every rated
support bearing wears by rolling-contact fatigue (docs/life.md). Over a duty cycle each
step uses up the fraction ``dt / L10`` of the life it would have if it lasted forever;
Miner's rule adds them up. The commute carries the bike's speed, so the life comes out in
kilometres as well as hours.
"""

from pathlib import Path

import matplotlib.pyplot as plt

from ballcvt import Variator, load_builtin
from ballcvt.api import CycleSettings, read_cycle

hub = Variator(*load_builtin("hub"))
# examples/cycles/ebike_commute.csv, from the repository root or from examples/gallery
# (where the documentation build runs the gallery)
folder = next(p for p in (Path("examples/cycles"), Path("../cycles")) if p.is_dir())
commute = read_cycle(folder / "ebike_commute.csv")
run = hub.cycle_life(
    commute, clamp_law="cam", settings=CycleSettings(target_input_speed_rpm=180, progress=False)
)
life = run.summary["life"]
print(
    f"{commute.distance / 1e3:.2f} km per commute; L10 {life['l10_hours']:.0f} h of "
    f"commuting = {life['l10_km']:.0f} km, limited by {life['limiting_element']}"
)

steps = run.steps
elements = {k: v["l10_hours"] for k, v in life["elements"].items()}
names = sorted(elements, key=elements.get)
fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6.5), layout="constrained")
top.semilogy(steps.time / 60, steps.l10_hours, ".", ms=2)
top.set_xlabel("time [min]")
top.set_ylabel("system L10 at the step [h]")
top.set_title("hub, cam clamping, 180 rpm input: life at each step")
bottom.barh(names, [elements[k] for k in names])
bottom.set_xscale("log")
bottom.axvline(life["l10_hours"], color="r", label=f"drive: {life['l10_hours']:.0f} h")
bottom.set_xlabel("Miner L10 over the commute [h]")
bottom.legend()
plt.show()
