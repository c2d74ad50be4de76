#!/usr/bin/python3
"""A rigid ball dragged without friction across a soft block (issue 14,
input/stress/ball/ball_stas_soft_mu0.deck, STAS): the block is hyperelastic and the penalty
normal contact has a potential, so the drag force is the derivative of the total potential
with respect to the ball's position, and its work over the slide is the potential's change.
The ball slides from x = 3 to x = 7 on a block (and mesh) symmetric about x = 5, so the two
end states are mirror images with equal potentials: the drag's work over the slide must vanish
(trapezoidal rule on the steps; it does so exactly only if the force at each position is the
mirror image of the force at the mirrored position, i.e. if the run is free of path dependence).
Measured: 2e-15 of mean |Fz| x slide; 100 steps without a cut-back. About 15 s on one thread."""
import csv
import os
import subprocess
import sys

import stress_script

args = stress_script.parse_args()
source = stress_script.ironing_deck_text(args, "ball_stas_soft_mu0.deck", folder="ball")
for text in ("contact stas", "steps 100 dt=0.01", 'ux "4*max(t-0.2,0)/0.8"'):
    assert text in source, f"the deck no longer says {text!r}"
contact = [line for line in source.splitlines() if line.startswith("contact ")]
assert len(contact) == 1 and " mu=" not in contact[0], "the deck's contact is not frictionless"
deck = os.path.join(args.scratch, "ball_stas_soft_mu0.deck")
open(deck, "w").write(source)
r = subprocess.run([args.covcontact, "run", "--threads", "1", deck, "-o",
                    os.path.join(args.scratch, "ball.h5")], capture_output=True, text=True,
                   timeout=280)
if r.returncode != 0 or "completed: 100 steps" not in r.stdout or "0 cut-backs" not in r.stdout:
    sys.exit(f"FAIL: the run did not complete 100 steps without a cut-back (exit "
             f"{r.returncode}):\n{r.stdout[-3000:]}{r.stderr[-2000:]}")
rows = list(csv.DictReader(open(os.path.join(args.scratch, "ball_reactions.csv"))))
t = [0.0] + [float(row["time"]) for row in rows]
fx = [0.0] + [float(row["contact_ball_Fx"]) for row in rows]
fz = [0.0] + [float(row["contact_ball_Fz"]) for row in rows]
x = [4 * max(tk - 0.2, 0) / 0.8 for tk in t]
work = sum(0.5 * (fx[k] + fx[k - 1]) * (x[k] - x[k - 1]) for k in range(1, len(t)))
sliding = [k for k in range(len(t)) if t[k] > 0.2 + 1e-9]
scale = sum(abs(fz[k]) for k in sliding) / len(sliding) * 4
peak = max(abs(fx[k]) for k in sliding)
print(f"drag work {work:.3e}, mean |Fz| x slide {scale:.4g}, peak |Fx| {peak:.3g}")
failures = []
if abs(work) > 1e-9 * scale:
    failures.append(f"the frictionless drag did work {work:.3e} = {work / scale:.2e} of "
                    "mean |Fz| x slide (bound 1e-9)")
if peak < 1e-3 * scale / 4:
    failures.append(f"peak |Fx| {peak:.3g}: the drag force vanishes, so the check tests nothing")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
