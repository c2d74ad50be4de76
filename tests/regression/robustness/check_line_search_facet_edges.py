#!/usr/bin/python3
"""The line search over the facet edges of a faceted master (issue 14): STS on the faceted
ironing die (ironing_sts_mu03_wide.deck) with `newton predictor=extrapolate line_search=yes`.
In developed sliding, points cross facet edges in the iterates, and each crossing makes the
residual jump by a fraction of the point's force that no shorter step removes. Measured against
the iterate's own residual alone, the line search let the iterates creep up to the edges: the
step at t = 0.24 was cut back, and from t = 0.4 the iterates sat at a relative residual of
5e-7 for 30 iterations, cut back after cut-back, until the run stopped at t = 0.3995 (28
cut-backs). A trial whose points cross edges for the first time in the attempt is now measured
against the attempt's largest residual (newton.hpp, kLineSearchDecrease).

45 steps (t = 0.45) must run without a cut-back, and every step must end at the state the same
deck reaches without the line search: the contact force on the die and the reaction at the
slab's bottom agree to 1e-8 of the largest force (measured: 1.3e-12 over the whole deck).
About 35 s on one thread."""
import csv
import os
import sys

import stress_script

STEPS = 45
args = stress_script.parse_args()
deck = "ironing_sts_mu03_wide.deck"
must = ("contact sts", "edge=fade")
searched = stress_script.run_ironing_steps(args, deck, STEPS, must, newton="predictor=extrapolate "
                                           "line_search=yes", label="_line_search")
plain = stress_script.run_ironing_steps(args, deck, STEPS, must, newton="predictor=extrapolate",
                                        label="_plain")
failures = []
cutbacks = [line for line in searched.stdout.splitlines() if line.startswith("cut-back at")]
if cutbacks:
    failures.append("cut-backs with the line search:\n" + "\n".join(cutbacks))
if f"completed: {STEPS} steps" not in searched.stdout:
    failures.append(f"the line-search run did not complete {STEPS} steps:\n"
                    + searched.stdout[-2000:])


def forces(label):
    path = os.path.join(args.scratch, f"ironing_sts_mu03_wide_{STEPS}{label}_reactions.csv")
    return {round(float(row["time"]), 9): row for row in csv.DictReader(open(path))}


with_search, without = forces("_line_search"), forces("_plain")
if sorted(with_search) != sorted(without):
    failures.append(f"the runs converged at different times: {sorted(with_search)} against "
                    f"{sorted(without)}")
else:
    columns = ("contact_die_Fx", "contact_die_Fz", "slab_bottom_Fx", "slab_bottom_Fz")
    largest = max(abs(float(row[c])) for row in without.values() for c in columns)
    worst = max(abs(float(with_search[t][c]) - float(without[t][c]))
                for t in without for c in columns) / largest
    print(f"largest force difference: {worst:.2e} of the largest force ({len(without)} steps)")
    if worst > 1e-8:
        failures.append(f"the line-search run ends its steps elsewhere: {worst:.2e} of the "
                        "largest force")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
