#!/usr/bin/python3
"""NTS on the smoothed ironing die with the energy criterion (issue 14):
input/stress/ironing/ironing_nts_mu03_wide_smooth.deck run to t = 0.45 with --newton-log. Slab
nodes pressing on a Nagata patch edge, where the die's normal jumps, have no equilibrium on
either patch and were handed back and forth between the two in every Newton iteration: the
relative residual stalled at 8e-11 (relative energy 1.5e-16 against the criterion's 1e-16) with
3 points changing segment each iteration, and step 43 was cut back after 30 iterations (12
cut-backs by t = 0.51 before kHopStayTolerance). Asserted: the run completes without a cut-back
(line-search retries allowed, at most 2: measured 2, in steps 8 and 21), in at most 4 Newton
iterations per step on average in steps 22-45 (measured 3.33)."""
import os
import sys

import stress_script

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import progress_lines  # noqa: E402  (tests/support)

args = stress_script.parse_args()
r = stress_script.run_ironing_steps(args, "ironing_nts_mu03_wide_smooth.deck", 45,
                                    must_contain=("surface=smooth",))
failures = []
cutbacks = [line for line in (r.stdout + r.stderr).splitlines() if line.startswith("cut-back at")]
retries = [line for line in cutbacks if "retrying the step with line search" in line]
if len(cutbacks) > len(retries):
    failures.append("cut-backs:\n" + "\n".join(set(cutbacks) - set(retries)))
if len(retries) > 2:
    failures.append(f"{len(retries)} line-search retries (at most 2):\n" + "\n".join(retries))
steps = progress_lines.converged_steps(r.stdout)
developed = [steps[k] for k in range(22, 46) if k in steps]
if len(developed) != 24:
    failures.append(f"steps 22-45 converged: {sorted(k for k in steps if k >= 22)}")
mean = sum(developed) / max(len(developed), 1)
print(f"steps 22-45: {sum(developed)} Newton iterations, {mean:.2f} per step; "
      f"{len(retries)} line-search retries")
if mean > 4:
    failures.append(f"{mean:.2f} Newton iterations per step in steps 22-45 (at most 4)")
if failures:
    sys.exit("\n".join(failures))
