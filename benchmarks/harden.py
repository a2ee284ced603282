"""Hardening campaign: thousands of operating points on random designs, every outcome counted.

Run: ``python benchmarks/harden.py [--designs 500] [--conditions 4] [--seed 1]``
(prints the counts; the README's reliability section records them).

Half the designs are drawn over every value the validators accept (log-uniform sizes from
1 mm to 10 m, aspect ratios 0.05-100, contact angles 0.5-89.5 deg, 3-64 balls, grooves from
nearly conforming to straight, any tilt safety factor, creep limits 0.01-0.9), half around
Table I (sizes x 0.3-3, angles +-20 deg, 3-16 balls); both architectures. A drawn design
that cannot be built is counted with the reason it was refused. For each
feasible design, ``--conditions`` operating conditions (ratio across the whole usable range,
clamping force 1e-2 to 1e2 times, and speed 1e-2 to 30 times, the Table I point scaled to
the ball size at equal pressure and rolling speed) are each evaluated at five torques,
0 to 1.5 x the limiting torque: by `Variator.solve` point by point, and by one
`Variator.sweep` over the five torques, which must agree.

Every point ends as exactly one of:

* converged (with or without validity warnings);
* flagged with a reason: beyond the traction capacity (`TractionLimitError`), no
  equilibrium even at zero torque (`NoEquilibriumError`), refused input (`InputError`,
  e.g. a clamp whose pressure overflows the viscosity law), not converged
  (`ConvergenceError`, with its message);
* a silent failure: NaN or inf in a result, eta outside [0, 1), a negative loss, Eq. 38 and
  Eq. 39 apart by more than the residual bound, creep and traction of opposite signs, or
  the sweep and `solve` disagreeing (status, or eta by more than 1e-6);
* a bug: any other exception.

The target is 0 silent failures and 0 bugs.
"""

from __future__ import annotations

import argparse
import collections
import math
import time
import traceback
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np
from tqdm import tqdm

from ballcvt import ConvergenceError, InputError, TractionLimitError, Variator, __version__, load_builtin
from ballcvt.errors import NoEquilibriumError

BASE_DESIGN, BASE_FLUID = load_builtin()
FRACTIONS = (0.0, 0.3, 0.7, 0.95, 1.5)


def log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def draw_design(rng, wide):
    """A design (may be infeasible): over the validators' whole ranges if ``wide``, else
    around Table I (sizes x 0.3-3, angles +-20 deg, 3-16 balls)."""
    if wide:
        groove = lambda: math.inf if rng.random() < 0.2 else 1.0 + log_uniform(rng, 1e-2, 100)  # noqa: E731
        rs = log_uniform(rng, 1e-3, 10.0)
        return dict(
            aspect_ratio=log_uniform(rng, 0.05, 100.0), roller_radius=rs,
            theta0_deg=rng.uniform(0.5, 89.5), theta2_deg=rng.uniform(0.5, 89.5),
            alpha_deg=rng.uniform(0.0, 89.5), n_rollers=int(rng.integers(3, 65)),
            roller_bearing_diameter=rs * log_uniform(rng, 0.05, 2.0),
            idler_bearing_diameter=rs * log_uniform(rng, 0.05, 2.0),
            disc_groove_ratio=groove(), idler_groove_ratio=groove(),
            single_idler_groove_ratio=groove(), tilt_safety_factor=rng.uniform(0.05, 1.0),
            creep_limit=log_uniform(rng, 1e-2, 0.9),
            min_roller_gap=rs * log_uniform(rng, 1e-4, 0.5))
    f = lambda: log_uniform(rng, 0.3, 3.0)  # noqa: E731
    rs = BASE_DESIGN.roller_radius * f()
    return dict(
        aspect_ratio=BASE_DESIGN.aspect_ratio * f(), roller_radius=rs,
        theta0_deg=45.0 + rng.uniform(-20, 20), theta2_deg=45.0 + rng.uniform(-20, 20),
        alpha_deg=10.0 + rng.uniform(-8, 20), n_rollers=int(rng.integers(3, 17)),
        roller_bearing_diameter=rs / 3 * f(), idler_bearing_diameter=rs / 3 * f(),
        disc_groove_ratio=1.0 + 1.4548 * f(), idler_groove_ratio=1.0 + 1.4548 * f(),
        single_idler_groove_ratio=math.inf if rng.random() < 0.5 else 1.0 + 10 * f(),
        tilt_safety_factor=rng.uniform(0.5, 0.95), creep_limit=rng.uniform(0.05, 0.2),
        min_roller_gap=0.001 * f())


def feasible_design(rng, refused, wide):
    """Draw until a design is accepted; count every refusal by the quantity named."""
    while True:
        fields = draw_design(rng, wide)
        if rng.random() < 0.5:   # bias half the draws towards designs that fit
            k, rs, g = fields["aspect_ratio"], fields["roller_radius"], fields["min_roller_gap"]
            s = min(0.999, (1 + g / (2 * rs)) / (1 + k))
            fields["n_rollers"] = int(rng.integers(3, max(4, int(math.pi / math.asin(s)) + 1)))
        try:
            return BASE_DESIGN.replace(name="random", **fields)
        except InputError as exc:
            refused[exc.quantity] += 1


def silent_failures(v, r):
    """The silent-failure checks of one converged result; returns a list of reasons."""
    bad = []
    numbers = [r.eta, r.eta_loss, r.eta_speed, r.eta_torque, r.input_torque, r.actual_ratio,
               r.tilt, *r.losses.values()]
    for c in r.contacts.values():
        numbers += [c.creep, c.spin, c.mu, c.chi, c.p_max, c.film_thickness, c.creep_loss,
                    c.spin_loss, c.lambda_ratio]
    if not all(math.isfinite(x) for x in numbers):
        bad.append("NaN or inf in the result")
    if not 0.0 <= r.eta < 1.0:
        bad.append(f"eta = {r.eta} outside [0, 1)")
    if min(r.losses.values()) < 0 or any(c.creep_loss < 0 or c.spin_loss < 0
                                         for c in r.contacts.values()):
        bad.append("negative loss")
    speeds = abs(r.roller_speed) + sum(abs(c.body_speed) for c in r.contacts.values())
    slack = v.design.n_rollers * r.clamp_force * v.design.roller_radius * r.residual_norm
    bound = 1e-12 + 2.0 * slack * speeds / r.input_power if r.input_power > 0 else 1e-9
    if abs(r.eta - r.eta_loss) > bound:
        bad.append(f"Eq. 38 - Eq. 39 = {r.eta - r.eta_loss:.3g} beyond the residual bound "
                   f"{bound:.3g}")
    if any(c.creep * c.mu < 0 for c in r.contacts.values()):
        bad.append("creep and traction of opposite signs")
    return bad


def run_condition(v, rng, counts, reasons, examples):
    lo, hi = v.ratio_range
    ratio = log_uniform(rng, lo, hi) if rng.random() < 0.8 else (lo if rng.random() < .5 else hi)
    scale = v.design.roller_radius / 0.03          # relative to the Table I ball
    clamp = 2000.0 * scale**2 * log_uniform(rng, 1e-2, 1e2)
    rpm = 2000.0 / scale * log_uniform(rng, 1e-2, 30.0)
    op = dict(clamp_force=clamp, input_speed_rpm=rpm)
    where = f"{v.architecture} idler, ratio {ratio:.4g}, clamp {clamp:.4g} N, {rpm:.4g} rpm"
    try:
        limit = v.limit_torque(ratio=ratio, **op)
    except (NoEquilibriumError, InputError) as exc:
        kind = "no equilibrium at zero torque" if isinstance(exc, NoEquilibriumError) else \
            f"refused input ({exc.quantity})"
        counts["flagged"] += len(FRACTIONS)
        reasons[kind] += len(FRACTIONS)
        return
    except Exception as exc:  # noqa: BLE001 - a bug: record it
        counts["bug"] += len(FRACTIONS)
        examples.append(f"BUG in limit_torque at {where}: {type(exc).__name__}: {exc}")
        return
    torques = [f * limit for f in FRACTIONS]
    solved = {}
    for t in torques:
        try:
            r = v.solve(ratio=ratio, output_torque=t, **op)
        except TractionLimitError:
            counts["flagged"] += 1
            reasons["beyond the traction capacity"] += 1
            continue
        except NoEquilibriumError:
            counts["flagged"] += 1
            reasons["no equilibrium at zero torque"] += 1
            continue
        except ConvergenceError as exc:
            counts["flagged"] += 1
            reasons[f"not converged: {str(exc)[:60]}"] += 1
            continue
        except InputError as exc:
            counts["flagged"] += 1
            reasons[f"refused input ({exc.quantity})"] += 1
            continue
        except Exception as exc:  # noqa: BLE001
            counts["bug"] += 1
            examples.append(f"BUG in solve at {where}, T2 {t:.4g}: {type(exc).__name__}: {exc}"
                            f"\n{traceback.format_exc(limit=3)}")
            continue
        bad = silent_failures(v, r)
        if bad:
            counts["silent"] += 1
            examples.append(f"SILENT at {where}, T2 {t:.4g}: {'; '.join(bad)}")
        else:
            counts["converged"] += 1
            if r.warnings:
                counts["converged with warnings"] += 1
                for w in r.warnings:
                    reasons[f"warning: {w.split(':')[0]}"] += 1
            solved[t] = r
    # the same torques through one sweep: status and eta must agree with solve
    try:   # the limit is the same function the sweep would call: given, not found twice
        ds = v.sweep(ratio=ratio, output_torque=torques, progress=False, limit_torque=limit,
                     **op)
    except Exception as exc:  # noqa: BLE001
        counts["bug"] += 1
        examples.append(f"BUG in sweep at {where}: {type(exc).__name__}: {exc}")
        return
    status = ds.status.values.ravel()
    eta = ds.eta.values.ravel()
    for j, t in enumerate(torques):
        if t in solved:
            if status[j] != 0 or abs(eta[j] - solved[t].eta) > 1e-6:
                counts["silent"] += 1
                examples.append(f"SILENT sweep != solve at {where}, T2 {t:.4g}: status "
                                f"{status[j]}, eta {eta[j]} vs {solved[t].eta}")
        elif status[j] == 0 and not np.isfinite(eta[j]):
            counts["silent"] += 1
            examples.append(f"SILENT sweep NaN without a flag at {where}, T2 {t:.4g}")


def run_designs(seed, first, count, conditions):
    """Designs ``first ... first + count - 1`` (each from its own seeded generator)."""
    refused, counts, reasons = (collections.Counter() for _ in range(3))
    examples, archs = [], collections.Counter()
    for i in range(first, first + count):
        rng = np.random.default_rng([seed, i])
        v = None
        while v is None:                      # redraw until one architecture accepts it
            design = feasible_design(rng, refused, wide=i % 4 >= 2)
            for arch in (("double", "single") if i % 2 == 0 else ("single", "double")):
                try:
                    v = Variator(design, BASE_FLUID, arch)
                    break
                except InputError as exc:     # the architecture's own checks (Eqs. F4-F6)
                    refused[f"{exc.quantity} ({arch})"] += 1
        archs[v.architecture] += 1
        for _ in range(conditions):
            run_condition(v, rng, counts, reasons, examples)
    return refused, counts, reasons, examples, archs


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=500)
    parser.add_argument("--conditions", type=int, default=4,
                        help="operating conditions per design (x 5 torques)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    chunks = [(args.seed, int(c[0]), len(c), args.conditions)
              for c in np.array_split(np.arange(args.designs), 4 * args.workers) if len(c)]
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        futures = [pool.submit(run_designs, *chunk) for chunk in chunks]
        with tqdm(total=args.designs, desc="hardening campaign", unit="design") as bar:
            for f in as_completed(futures):
                bar.update(chunks[futures.index(f)][2])
        parts = [f.result() for f in futures]
    refused, counts, reasons, archs = (sum((p[k] for p in parts), collections.Counter())
                                       for k in (0, 1, 2, 4))
    examples = [e for p in parts for e in p[3]]
    elapsed = time.perf_counter() - start
    points = counts["converged"] + counts["flagged"] + counts["silent"] + counts["bug"]
    print(f"ballcvt {__version__} hardening campaign, seed {args.seed}: {sum(archs.values())} "
          f"feasible designs ({archs['double']} double, {archs['single']} single idler), "
          f"{points} operating points, {elapsed:.0f} s on {args.workers} processes")
    print(f"designs refused while drawing: {sum(refused.values())}")
    for name, n in refused.most_common():
        print(f"  {n:6d}  {name}")
    print(f"converged:        {counts['converged']:6d}  (with validity warnings: "
          f"{counts['converged with warnings']})")
    print(f"flagged:          {counts['flagged']:6d}")
    print(f"silent failures:  {counts['silent']:6d}")
    print(f"bugs:             {counts['bug']:6d}")
    print("reasons (flags and warnings):")
    for name, n in reasons.most_common():
        print(f"  {n:6d}  {name}")
    for text in examples[:20]:
        print(text)
    return 0 if counts["silent"] == 0 and counts["bug"] == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
