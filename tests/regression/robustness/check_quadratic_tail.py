#!/usr/bin/python3
"""The quadratic tail of Newton in a sliding step with the exact tangent (issue 14).

Runs input/stress/large_slip_step.deck (example 6.1's block pressed, then dragged by 10 u_cr in
ONE step: every contact point slides) with `tangent=exact` and reads the per-iteration history
from the results file (/convergence). With a consistent tangent Newton converges quadratically
once the active set has settled (theory, not a stored number): for the last three recorded
residuals r_{k-1}, r_k, r_{k+1} of the sliding step (relative to its first, each the residual at
the start of an iteration) the order estimate p = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) must be at
least 1.8 (2 in theory; linear convergence, as with an inconsistent tangent, gives p near 1).
The residuals used must lie above round-off (1e-13 relative); the constant r_{k+1} / r_k^2 is
printed, not asserted."""
import math
import os
import subprocess
import sys

import h5py

import stress_script

args = stress_script.parse_args()
deck = stress_script.exact_large_slip_deck(args)
results = os.path.join(args.scratch, "r.h5")
run = subprocess.run([args.covcontact, "run", "--threads", "1", "-q", deck, "-o", results],
                     capture_output=True, text=True, timeout=240)
failures = []
if run.returncode != 0:
    failures.append(f"exit code {run.returncode}: {run.stderr}")
else:
    with h5py.File(results, "r") as f:
        rows = f["convergence"][...]
    step = rows[rows["step"] == 2]
    step = step[step["attempt"] == step["attempt"].max()]
    r = [float(x) for x in step["relative_residual"]]
    print("sliding step, relative residuals per iteration:", " ".join(f"{x:.3e}" for x in r))
    if len(r) < 3:
        failures.append(f"only {len(r)} iterations: no tail to measure")
    else:
        a, b, c = r[-3], r[-2], r[-1]
        if min(a, b, c) <= 1e-13:
            failures.append(f"tail at round-off: {a:.3e} {b:.3e} {c:.3e}")
        else:
            order = math.log(c / b) / math.log(b / a)
            print(f"order estimate p = {order:.2f}, r_k+1 / r_k^2 = {c / b**2:.3e}")
            if not order >= 1.8:
                failures.append(f"order estimate {order:.2f} < 1.8 ({a:.3e} {b:.3e} {c:.3e})")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
