#!/usr/bin/python3
"""Issue 16 part 2: the smooth-master study's table (docs/verification/smooth_master.md).

usage: smooth_master_table.py [--run] [--dir DIR] [--densities 8,16,32] [--shell 16|64]

With --run, runs input/verification/smooth_master/analytic.deck and trough_nx<N>_<faceted|smooth>.deck
for each density in DIR (default: a temporary directory) with build/src/app/covcontact; then reads
the reactions CSVs (STEM_reactions.csv) in DIR and prints, per meshed run against the analytic
(STAS) run:

  force difference: max over the sliding steps of |F - F_analytic| / |F_analytic| (F: the force
      on the driven edges top_edges, a vector);
  oscillation: peak-to-peak over the gross-sliding steps (5 to 36, see GROSS_SLIDING) of
      F_c - F_analytic,c after removing its local quadratic trend over 7 steps around each
      step, over the mean |F_analytic,c|, for c = x, y, z, the largest of the three. Segment
      crossings along x make every component jump, while the motion changes the force slowly;
      the shell's own discretization (its contact line crossing its element edges, steps
      17-25) shows in every run alike and mostly cancels in the difference;
  mesh convergence: the force difference (as above) to the finest smooth run;
  Coulomb check (an independent reference): in gross sliding the contact force on the shell
      must be mu N along minus the slip velocity. With n the trough's normal at the foot point
      of the prescribed motion (the contact line, eq. (127) with the exact 0.99-offset of
      model.inc) and the slip the tangential part of the edges' prescribed displacement in the
      step, the largest over steps 5-36 of | |F_t| / (mu N) - 1 | and of the angle between
      -F_t and the slip;
  ratio: the faceted run's oscillation over the smooth run's;
  iterations: Newton iterations per step in the spiral, and the analytic run's.
"""
import argparse
import csv
import os
import subprocess
import sys
import math
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECKS = os.path.join(ROOT, "input", "verification", "smooth_master")
BINARY = os.path.join(ROOT, "build", "src", "app", "covcontact")
# Steps (1: press; 2..41: spiral) of gross sliding: from the 4th spiral step on, sliding is fully
# developed; after step 36 the analytic (STAS) run has a kink of its own (Fx +7 % and +12 % in
# steps 40-41, where its Gauss points on the shell cross into contact) that no sts run has.
GROSS_SLIDING = (5, 36)
WINDOW = 7  # steps of the local quadratic trend removed before the peak-to-peak


def read(path):
    rows = list(csv.DictReader(open(path)))
    t = [float(r["time"]) for r in rows]
    its = [int(r["iterations"]) for r in rows]
    f = [[float(r["top_edges_F" + c]) for c in "xyz"] for r in rows]
    return t, its, f


def run(deck, directory):
    subprocess.run([BINARY, "run", os.path.join(DECKS, deck)], cwd=directory, check=True,
                   stdout=subprocess.DEVNULL)


def quadratic_residual(t, d):
    """d minus its least-squares quadratic in t (normal equations, t centred and scaled)."""
    tm = sum(t) / len(t)
    ts = max(abs(x - tm) for x in t) or 1.0
    u = [(x - tm) / ts for x in t]
    a = [[sum(x ** (i + j) for x in u) for j in range(3)] for i in range(3)]
    b = [sum(y * x ** i for x, y in zip(u, d)) for i in range(3)]
    for i in range(3):  # Gauss elimination, 3 x 3 and well conditioned after scaling
        for k in range(i + 1, 3):
            m = a[k][i] / a[i][i]
            a[k] = [akj - m * aij for akj, aij in zip(a[k], a[i])]
            b[k] -= m * b[i]
    c = [0.0] * 3
    for i in (2, 1, 0):
        c[i] = (b[i] - sum(a[i][j] * c[j] for j in range(i + 1, 3))) / a[i][i]
    return [y - (c[0] + c[1] * x + c[2] * x * x) for x, y in zip(u, d)]


def oscillation(t, f, reference):
    """Peak-to-peak of the high-passed difference to the analytic run over the mean force."""
    gross = [k for k in range(len(t)) if GROSS_SLIDING[0] <= k + 1 <= GROSS_SLIDING[1]]
    worst = 0.0
    half = WINDOW // 2
    for c in range(3):
        d = [f[k][c] - reference[k][c] for k in range(len(t))]
        # The difference minus its local quadratic trend over WINDOW steps around each step:
        # what changes faster than the motion itself, i.e. the segment crossings.
        high = []
        for k in gross[half:len(gross) - half]:
            window = range(k - half, k + half + 1)
            high.append(quadratic_residual([t[j] for j in window], [d[j] for j in window])[half])
        mean = sum(abs(reference[k][c]) for k in gross) / len(gross)
        worst = max(worst, (max(high) - min(high)) / mean)
    return worst


MU, C = 0.3, 0.05


def driven_position(t):
    """Prescribed position (offset from the start) of the driven edges and the foot point a."""
    s = 0.01 * max(t - 1, 0)
    q = math.sqrt(1 + 4 * C * C * s * s)
    return [s * (1 - 2 * C * 0.99 / q), 0.02 * max(t - 1, 0),
            -0.01 * min(t, 1) + C * s * s + 0.99 / q - 0.99], s


def coulomb(t, f):
    """Largest deviation from Coulomb's law in gross sliding: (|F_t|/(mu N) - 1, angle deg)."""
    worst_ratio, worst_angle = 0.0, 0.0
    for k in range(GROSS_SLIDING[0] - 1, GROSS_SLIDING[1]):
        x1, a = driven_position(t[k])
        x0, _ = driven_position(t[k - 1])
        n = [-2 * C * a, 0.0, 1.0]
        n = [x / norm(n) for x in n]
        contact = [-x for x in f[k]]  # the force of the trough on the shell
        normal = sum(c * m for c, m in zip(contact, n))
        ft = [c - normal * m for c, m in zip(contact, n)]
        v = [b - a0 for b, a0 in zip(x1, x0)]
        vn = sum(c * m for c, m in zip(v, n))
        vt = [c - vn * m for c, m in zip(v, n)]
        cosine = -sum(p * q for p, q in zip(ft, vt)) / (norm(ft) * norm(vt))
        worst_ratio = max(worst_ratio, abs(norm(ft) / (MU * normal) - 1))
        worst_angle = max(worst_angle, math.degrees(math.acos(min(1.0, cosine))))
    return worst_ratio, worst_angle


def norm(v):
    return math.sqrt(sum(x * x for x in v))


def sliding_mean(t, its):
    spiral = [i for tk, i in zip(t, its) if tk > 1 + 1e-9]
    return sum(spiral) / len(spiral)


def compare(directory, stem, reference):
    t, its, f = read(os.path.join(directory, stem + "_reactions.csv"))
    tr, itr, fr = reference
    if len(t) != len(tr) or max(abs(a - b) for a, b in zip(t, tr)) > 1e-9:
        raise SystemExit(f"{stem}: steps differ from the analytic run")
    diff = max(norm([a - b for a, b in zip(f[k], fr[k])]) / norm(fr[k])
               for k in range(len(t)) if t[k] > 1 + 1e-9)
    return {"diff": diff, "osc": oscillation(t, f, fr), "its": sliding_mean(t, its),
            "total": sum(its), "coulomb": coulomb(t, f)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--run", action="store_true")
    parser.add_argument("--dir", default=None)
    parser.add_argument("--densities", default="8,16,32")
    parser.add_argument("--shell", choices=["16", "64"], default="16",
                        help="shell elements around the semi-cylinder: the study's decks (16) or "
                             "their *_nt64 copies")
    args = parser.parse_args()
    suffix = "" if args.shell == "16" else "_nt64"
    directory = args.dir or tempfile.mkdtemp(prefix="smooth_master_")
    densities = [int(n) for n in args.densities.split(",")]
    if args.run:
        run(f"analytic{suffix}.deck", directory)
        for n in densities:
            for kind in ("faceted", "smooth"):
                run(f"trough_nx{n}_{kind}{suffix}.deck", directory)
    reference = read(os.path.join(directory, f"analytic{suffix}_reactions.csv"))
    t, its, f = reference
    analytic = sliding_mean(t, its)
    ratio, angle = coulomb(t, f)
    print(f"analytic (STAS): {analytic:.2f} iterations per spiral step, {sum(its)} in all; "
          f"Coulomb check: |F_t|/(mu N) off by {100 * ratio:.1f} %, angle {angle:.1f} deg")
    finest = read(os.path.join(directory,
                               f"trough_nx{max(densities)}_smooth{suffix}_reactions.csv"))
    print("| nx | h | master | force difference | to finest smooth | oscillation | "
          "faceted/smooth | iterations/step (analytic) | Coulomb: ratio, angle |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in densities:
        result = {k: compare(directory, f"trough_nx{n}_{k}{suffix}", reference)
                  for k in ("faceted", "smooth")}
        for kind in ("faceted", "smooth"):
            r = result[kind]
            ratio = (f"{result['faceted']['osc'] / r['osc']:.1f}" if kind == "smooth" else "")
            converged = compare(directory, f"trough_nx{n}_{kind}{suffix}", finest)["diff"]
            print(f"| {n} | {4 / n:.3g} | {kind} | {100 * r['diff']:.2f} % | "
                  f"{100 * converged:.2f} % | {100 * r['osc']:.3f} % | {ratio} | "
                  f"{r['its']:.2f} ({analytic:.2f}) | {100 * r['coulomb'][0]:.1f} %, "
                  f"{r['coulomb'][1]:.1f} deg |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
