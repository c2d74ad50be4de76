#!/usr/bin/python3
"""The extrapolating predictor (`newton predictor=extrapolate`, issue 14): the first iterate of a
step is the converged state plus the last step's increment scaled to dt, and the relative norms
are measured against the step's increment (newton.cpp), so the energy criterion asks what it
asks without the predictor.

1. Paper example 6.1(a) (101 steps) with and without the predictor: the contact and reaction
   forces of every step agree to 1e-8 of the largest force (the converged states are the same),
   no cut-back, and fewer Newton iterations (measured 306 against 380). Measured against its own
   first residual (about 1e-5 of the step's), the first slide step asked for round-off and the
   run stopped after 10 cut-backs: this part fails on that.
   A run restarted from step 50 of that results file (whose restart data carry the step's
   increment, last_increment) takes the same iterations per step as the full run, and its
   energy account starts at the restart state.
2. The smoothed ironing die (ironing_sts_mu03_wide_smooth.deck, energy criterion 1e-16) with the
   predictor: at most 4 Newton iterations per step on average in developed sliding, t in
   (0.4, 1] (issue 14's target; measured 3.35, without the predictor 4.35), no cut-back, the
   mean die force of the run without the predictor (11.02), and the quadratic tail of the exact
   tangent in its developed steps (the median of r_(k+1) / r_k^2 at most 10).
3. The die as a rigid cylinder (ironing_stas_mu03.deck, its first 22 steps) with the predictor:
   at the press -> drag corner (t = 0.2) the rigid surface's motion turns, so step 21 starts
   from the converged state; the log says so for that step alone, the step takes the default
   predictor's iterations (measured 6 and 6; 17 when it was extrapolated) and every step's die
   forces agree with the default predictor's run to 1e-8 of the largest."""
import csv
import os
import re
import subprocess
import sys

import h5py

import stress_script

args = stress_script.parse_args()
failures = []


def with_predictor(text):
    return re.sub(r"^solve(.*)$", r"solve\1\n  newton predictor=extrapolate", text, count=1,
                  flags=re.M)


def run(deck_text, name):
    deck = os.path.join(args.scratch, name + ".deck")
    open(deck, "w").write(deck_text)
    results = os.path.join(args.scratch, name + ".h5")
    r = subprocess.run([args.covcontact, "run", "--threads", "1", deck, "-o", results],
                       capture_output=True, text=True, timeout=280)
    if r.returncode != 0:
        sys.exit(f"{name}: exit {r.returncode}\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    summary = re.search(r"completed: (\d+) steps, (\d+) Newton iterations.*?(\d+) cut-backs",
                        r.stdout)
    rows = list(csv.DictReader(open(os.path.join(args.scratch, name + "_reactions.csv"))))
    logs[name] = r.stdout
    return int(summary.group(2)), int(summary.group(3)), rows


logs = {}


# 1. Example 6.1(a): the same states in fewer iterations.
paper = os.path.abspath(os.path.join(args.decks, "../paper"))
source = open(os.path.join(paper, "sliding_block_6_1a.deck")).read()
source = re.sub(r'^(include|mesh)(\s+)"([^"/][^"]*)"',
                lambda m: f'{m[1]}{m[2]}"{os.path.join(paper, m[3])}"', source, flags=re.M)
# (an include's own paths stay relative to the include)
assert os.path.join(paper, "sliding_block_6_1.inc") in source
plain_its, plain_cuts, plain = run(source, "6_1a_plain")
pred_its, pred_cuts, pred = run(with_predictor(source), "6_1a_predictor")
forces = [k for k in plain[0] if k not in ("step", "time", "iterations")]
scale = max(abs(float(row[k])) for row in plain for k in forces)
worst = 0.0
if len(pred) != len(plain):
    failures.append(f"6.1(a): {len(pred)} steps with the predictor, {len(plain)} without")
for a, b in zip(plain, pred):
    if float(a["time"]) != float(b["time"]):
        failures.append(f"6.1(a): step times differ ({a['time']} against {b['time']})")
        break
    worst = max(worst, max(abs(float(a[k]) - float(b[k])) for k in forces) / scale)
print(f"6.1(a): {plain_its} Newton iterations without the predictor, {pred_its} with it "
      f"({pred_cuts} cut-backs); largest force difference {worst:.2e} of the largest force")
if worst > 1e-8:
    failures.append(f"6.1(a): forces differ by {worst:.2e} of the largest force (at most 1e-8)")
if pred_cuts != 0:
    failures.append(f"6.1(a): {pred_cuts} cut-backs with the predictor")
if pred_its >= plain_its:
    failures.append(f"6.1(a): {pred_its} iterations with the predictor, {plain_its} without")

# A restart from step 50 predicts its first step as the full run did.
restarted = os.path.join(args.scratch, "6_1a_restarted.h5")
r = subprocess.run([args.covcontact, "run", "--threads", "1",
                    os.path.join(args.scratch, "6_1a_predictor.deck"), "--restart",
                    os.path.join(args.scratch, "6_1a_predictor.h5"), "--from-step", "50", "-o",
                    restarted], capture_output=True, text=True, timeout=280)
if r.returncode != 0:
    sys.exit(f"restart: exit {r.returncode}\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
rows = list(csv.DictReader(open(os.path.join(args.scratch, "6_1a_restarted_reactions.csv"))))
full = {int(row["step"]): int(row["iterations"]) for row in pred}
again = {int(row["step"]): int(row["iterations"]) for row in rows}
differing = [k for k in again if again[k] != full.get(k)]
print(f"6.1(a) restarted from step 50: steps {min(again)}-{max(again)}, iterations differ in "
      f"{len(differing)} steps")
if min(again) != 51 or max(again) != 101 or differing:
    failures.append(f"restart from step 50: steps {min(again)}-{max(again)}, iterations differ "
                    f"from the full run's in steps {differing[:10]}")

# The restarted run's energy account goes on from the sums and the reactions stored at the
# restart step (restart/energy_reactions): every step's external work is the full run's. Before
# the fifty-first session it started at the restart state with the reactions there unknown, its
# first step's work the one-sided r_51 . (u_51 - u_50) / 2; before that, it started at zero
# displacement and counted u_51 as the first increment.
def step_group(h5, step):
    return h5["steps"][f"{step:06d}"]


def external_work(h5, step):
    return float(step_group(h5, step)["energy"].attrs["external_work"])


with h5py.File(os.path.join(args.scratch, "6_1a_predictor.h5"), "r") as whole, \
        h5py.File(restarted, "r") as continued:
    works = [(external_work(continued, k), external_work(whole, k)) for k in range(51, 102)]
worst_work = max(abs(a - b) for a, b in works) / max(abs(b) for _, b in works)
print(f"restart from step 50, energy: the external work of steps 51-101 is the full run's to "
      f"{worst_work:.1e}")
if worst_work > 1e-8:
    failures.append(f"restart energy: the external work differs from the full run's by "
                    f"{worst_work:.1e}")

# 2. The smoothed ironing die in developed sliding.
ironing = stress_script.ironing_deck_text(args, "ironing_sts_mu03_wide_smooth.deck")
its, cuts, rows = run(with_predictor(ironing), "ironing_smooth_predictor")
developed = [int(r["iterations"]) for r in rows if float(r["time"]) > 0.4 + 1e-9]
per_step = sum(developed) / max(len(developed), 1)
fz = [-float(r["contact_die_Fz"]) for r in rows if float(r["time"]) > 0.4 + 1e-9]
mean_fz = sum(fz) / max(len(fz), 1)
print(f"ironing, smooth die: {len(rows)} steps, {its} Newton iterations, {cuts} cut-backs, "
      f"{per_step:.2f} per step in developed sliding ({len(developed)} steps), mean Fz {mean_fz:.4f}")
if len(rows) != 100 or len(developed) != 60:
    failures.append(f"ironing: {len(rows)} steps, {len(developed)} in developed sliding")
if cuts != 0:
    failures.append(f"ironing: {cuts} cut-backs")
if per_step > 4.0:
    failures.append(f"ironing: {per_step:.2f} Newton iterations per step in developed sliding "
                    "(at most 4)")
# The run without the predictor: mean Fz 11.02 over the same steps (sliding.md).
if abs(mean_fz - 11.02) > 0.01:
    failures.append(f"ironing: mean die force {mean_fz:.4f}, without the predictor 11.02")

# The quadratic tail of the developed steps (the decks' exact tangent): in each developed step
# the last two residuals recorded above 1e-7 (a hundred times the round-off floor of about 1e-9
# the runs reach) give C = r_{k+1} / r_k^2. Newton with a consistent tangent keeps C of order
# one (measured: median 0.87); the paper's tangent, inconsistent in sliding, converges linearly
# and its C grows as r_k shrinks (median 1.2e4 on this deck; sliding.md, thirty-seventh
# session). A step whose active set still changes at its tail can have a large C, so the
# median over the steps is asserted, and that most steps have a tail to measure.
with h5py.File(os.path.join(args.scratch, "ironing_smooth_predictor.h5"), "r") as h5:
    table = h5["convergence"][...]
tails = {}
for row in table:
    if float(row["time"]) > 0.4 + 1e-9 and float(row["residual"]) > 1e-7:
        step, attempt = int(row["step"]), int(row["attempt"])
        if step not in tails or tails[step][0] != attempt:
            tails[step] = (attempt, [])  # a later attempt replaces a failed one
        tails[step][1].append(float(row["residual"]))
constants = sorted(r[-1] / r[-2] ** 2 for _, r in tails.values() if len(r) >= 3)
median = constants[len(constants) // 2] if constants else float("inf")
print(f"ironing, smooth die: quadratic tail in {len(constants)} developed steps, median "
      f"r_(k+1) / r_k^2 = {median:.3g}")
if len(constants) < 30 or median > 10:
    failures.append(f"ironing: tail constant r_(k+1) / r_k^2 has median {median:.3g} over "
                    f"{len(constants)} developed steps (at most 10 over at least 30)")

# 3. The rigid cylinder through the press -> drag corner.
stas = stress_script.ironing_deck_text(args, "ironing_stas_mu03.deck")
assert "steps 100 dt=0.01" in stas
stas = stas.replace("steps 100 dt=0.01", "steps 22 dt=0.01")
_, _, stas_plain = run(stas, "stas_plain")
_, _, stas_pred = run(with_predictor(stas), "stas_predictor")
turns = [line for line in logs["stas_predictor"].splitlines() if "motion turns" in line]
corner = {name: int(rows[20]["iterations"]) for name, rows in
          (("default", stas_plain), ("extrapolated", stas_pred))}
die = [k for k in stas_plain[0] if k.startswith("contact_die_F")]
stas_scale = max(abs(float(row[k])) for row in stas_plain for k in die)
stas_worst = max(abs(float(a[k]) - float(b[k])) for a, b in zip(stas_plain, stas_pred)
                 for k in die) / stas_scale
print(f"rigid cylinder: {turns}; step 21 takes {corner['extrapolated']} iterations, "
      f"{corner['default']} with the default predictor; die forces differ by {stas_worst:.1e} "
      "of the largest")
if turns != ["predictor: step 21 starts from the converged state, not extrapolated: a rigid "
             "surface's motion turns at t = 0.2"]:
    failures.append(f"rigid cylinder: the log's turns are {turns}, expected step 21's alone")
if len(stas_pred) != 22 or corner["extrapolated"] != corner["default"]:
    failures.append(f"rigid cylinder: {len(stas_pred)} steps, step 21 takes "
                    f"{corner['extrapolated']} iterations, {corner['default']} with the default "
                    "predictor")
if stas_worst > 1e-8:
    failures.append(f"rigid cylinder: die forces differ by {stas_worst:.1e} of the largest from "
                    "the default predictor's (at most 1e-8)")
if failures:
    sys.exit("\n".join(failures))
