#!/usr/bin/python3
"""NTS on the faceted ironing die, mu = 0.6, die exactly as wide as the slab (issue 14): the
committed deck stops near t = 0.667, where a slab edge node just beyond the die's free edge
switches stick/slip through every cut-back down to dt = 1e-10. Its two contact states give
tangents of opposite determinant signs (one has the eigenvalue -0.35, the other none below
+0.0067: docs/verification/sliding.md, twenty-sixth session), a fold of the frictional problem
that no step size passes. The run must stop there with exit 3, keep its converged steps, name
the switching point and say that the tangent's determinant changes sign. Should the deck ever
complete, the fold claim is to be revisited, and this test says so.

Then, as the message advises, the run is continued from its last converged step with viscous
stabilisation (`newton stabilize=0.001`) to t = 0.7: it must pass the fold, and the
stabilisation's dissipation, which the run reports, must stay below a tenth of the work done
in that stretch (5 % measured), so that the answer is still mostly the quasi-static one. About
110 s on one thread."""
import os
import re
import subprocess
import sys

import stress_script

args = stress_script.parse_args()
r = stress_script.run_ironing_steps(args, "ironing_nts_mu06_equal.deck", 100,
                                    must_contain=("contact nts", "mu=0.6", "edge=fade",
                                                  "dieWidth=4"),
                                    may_fail=True, timeout=560)
output = r.stdout + r.stderr
failures = []
if r.returncode == 0:
    failures.append("the deck completed: the fold at t = 0.667 is gone, revisit "
                    "docs/verification/sliding.md (twenty-sixth session)")
elif r.returncode != 3:
    failures.append(f"exit {r.returncode}, expected 3 (a step failed after all cut-backs)")
stop = re.search(r"run diverged at t = ([0-9.]+)", output)
if not stop or not 0.6 < float(stop.group(1)) < 0.7:
    failures.append("no stop between t = 0.6 and 0.7")
kept = re.search(r"the (\d+) converged steps are kept in", output)
if not kept or int(kept.group(1)) < 60:
    failures.append("the converged steps before the fold are not reported kept")
if not re.search(r"kept changing in this attempt: die point \d+ at gmsh node \d+", output):
    failures.append("the switching points are not named")
if "the tangent's determinant changes sign between these iterations" not in output:
    failures.append("no fold verdict in the message")

# Continued with viscous stabilisation from the last converged step, to t = 0.7.
if r.returncode == 3:
    source = stress_script.ironing_deck_text(args, "ironing_nts_mu06_equal.deck")
    stabilized = os.path.join(args.scratch, "ironing_nts_mu06_equal_stabilized.deck")
    open(stabilized, "w").write(source.replace("steps 100 dt=0.01",
                                               "newton stabilize=0.001\n  steps 70 dt=0.01"))
    s = subprocess.run([args.covcontact, "run", "--threads", "1", stabilized, "--restart",
                        os.path.join(args.scratch, "ironing_nts_mu06_equal_100.h5"), "-o",
                        os.path.join(args.scratch, "ironing_nts_mu06_equal_stabilized.h5")],
                       capture_output=True, text=True, timeout=560)
    continued = s.stdout + s.stderr
    if s.returncode != 0 or not re.search(r"^step \d+ +t = 0\.7 of 0\.7 ", s.stdout, re.M):
        failures.append(f"the stabilised continuation did not reach t = 0.7 (exit {s.returncode})")
    share = re.search(r"viscous stabilisation dissipated \S+, (\S+) % of the work", continued)
    if not share:
        failures.append("the stabilised continuation does not report its dissipation")
    elif not 0 < float(share.group(1)) < 10:
        failures.append(f"the stabilisation took {share.group(1)} % of the work (limit 10 %)")
    else:
        # Each step line shows the share so far; the last one is the run's.
        lines = re.findall(r"^step \d+ .*stabilisation (\S+) % of the work$", s.stdout, re.M)
        if not lines or lines[-1] != share.group(1):
            failures.append(f"the step lines show the stabilisation's share as {lines[-1:]}, "
                            f"the run's is {share.group(1)} %")
    output += "\n--- continued with stabilisation ---\n" + continued
for f in failures:
    print("FAIL:", f)
if failures:
    print(output[-3000:])
sys.exit(1 if failures else 0)
