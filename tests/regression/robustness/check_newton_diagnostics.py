#!/usr/bin/python3
"""`covcontact run --newton-log --check-tangent` (issue 14) on input/stress/large_slip_step.deck:
one log line per Newton iteration with the contact counts, the iterations of each step add up to
the step's count, the tangent check prints 3 directions x 3 step sizes, and with the exact tangent
the random-direction check agrees with the central differences of the residual to 1e-6 at
h = 1e-6 |u| (an independent reference: the residual itself), each check names its three worst
equations, largest first; a malformed STEP:ITERATION is
rejected with a usage error."""
import os
import re
import subprocess
import sys

import stress_script

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import progress_lines  # noqa: E402  (tests/support)

args = stress_script.parse_args()
deck = stress_script.exact_large_slip_deck(args)
run = subprocess.run([args.covcontact, "run", "--threads", "1", "--newton-log", "--check-tangent",
                      "2:3", deck, "-o", os.path.join(args.scratch, "r.h5")],
                     capture_output=True, text=True, timeout=240)
failures = []
if run.returncode != 0:
    failures.append(f"exit code {run.returncode}: {run.stderr}")
last = {}
step_lines = []
for line in run.stdout.splitlines():
    logged = progress_lines.iteration_lines(line)
    if logged:
        last[logged[0][0]] = logged[0][2]
    converged = progress_lines.converged_step(line)
    if converged:
        step, iterations = converged
        step_lines.append(step)
        if last.get(step) != iterations:
            failures.append(f"step {step}: {iterations} iterations, log shows {last.get(step)}")
if step_lines != [1, 2]:
    failures.append(f"converged-step lines for steps {step_lines}, expected [1, 2]")
if sorted(last) != [1, 2]:
    failures.append(f"iteration lines for steps {sorted(last)}, expected [1, 2]")
checks = re.findall(r"tangent check: step 2 iteration 3 direction (\w+) h = ([0-9.e+-]+) \|u\|: "
                    r"\|K v - fd\| / \|fd\| = ([0-9.e+-]+)", run.stderr)
if len(checks) != 9:
    failures.append(f"{len(checks)} tangent check lines, expected 9:\n{run.stderr}")
for direction, h, error in checks:
    if direction.startswith("random") and float(h) == 1e-6 and not float(error) < 1e-6:
        failures.append(f"exact tangent vs differences along {direction}: {error}")
# Each check line is followed by its three equations with the largest |K v - fd|, largest first,
# named by the mesh file's node number and the component.
blocks = re.findall(r"tangent check: [^\n]*\n((?:  gmsh node \d+ [xyz]: K v - fd = \S+ \(K v = \S+, "
                    r"fd = \S+\)\n){3})", run.stderr)
if len(blocks) != 9:
    failures.append(f"{len(blocks)} checks with three worst equations listed, expected 9")
for block in blocks:
    gaps = [abs(float(g)) for g in re.findall(r"K v - fd = (\S+)", block)]
    if gaps != sorted(gaps, reverse=True):
        failures.append(f"worst equations not in descending order:\n{block}")
bad = subprocess.run([args.covcontact, "run", "--check-tangent", "2", deck],
                     capture_output=True, text=True, timeout=60)
if bad.returncode == 0 or "STEP:ITERATION" not in bad.stderr:
    failures.append(f"--check-tangent 2 accepted or unclear: {bad.returncode} {bad.stderr}")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
