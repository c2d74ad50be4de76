#!/usr/bin/python3
"""NTS on the faceted ironing die, mu = 0.3, die wider than the slab (issue 14): at step 50
(t = 0.5) a slab node crossing a facet edge of the die sets off state changes whose Newton
iterates fold a slab element (det J < 0). Cut back, the same fold came back at every step size
down to dt = 1e-10 and the run stopped at t = 0.495. The step is now retried with the line
search, which backs off from folded iterates: 51 steps must run without a single cut-back and
step 50 must be retried with the line search (docs/verification/sliding.md, fifteenth session;
the whole deck: 100 steps, 566 iterations, no cut-back). Since the twenty-first session the
plain attempt of step 50 ends before the fold, when its residual has stayed above its best for
four iterations (newton_stall.hpp); the fold's own retry is tested by
InvertedElement.OneDeepPunchStepIsRetriedWithLineSearch... About 30 s on one thread."""
import re
import sys

import stress_script

args = stress_script.parse_args()
r = stress_script.run_ironing_steps(args, "ironing_nts_mu03_wide.deck", 51,
                                    must_contain=("contact nts", "edge=fade"))
failures = []
retries = [line for line in (r.stdout + r.stderr).splitlines() if line.startswith("cut-back at")]
cutbacks = [line for line in retries if "retrying the step with line search" not in line]
if cutbacks:
    failures.append("cut-backs:\n" + "\n".join(cutbacks))
if not any(line.startswith("cut-back at step 50 ") for line in retries):
    failures.append("no line-search retry at step 50: the case no longer meets the hard step "
                    "it is meant to test; retries:\n" + "\n".join(retries))
# The start-up line that points a user at the smoothing (run_command.cpp): the die's cylinder
# is cut into facets that turn by 7 degrees across every edge along its axis.
if not re.search(r"contact 'die': the master is a curved surface meshed as facets \(\d+ of \d+ "
                 r"shared edges turn by more than 1 degree, up to 7\); .*surface=smooth", r.stdout):
    failures.append("no start-up hint that the die is a curved surface meshed as facets")
if "completed: 51 steps" not in r.stdout:
    failures.append("the run did not complete 51 steps:\n" + r.stdout[-2000:])
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
