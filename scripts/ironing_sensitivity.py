#!/usr/bin/python3
"""How the ironing decks' Newton iterations depend on the penalty, the step size and the mesh
(issue 14 asks it): each deck with `newton predictor=extrapolate` as committed (`base`), then
with one change at a time:
  - eps/4, eps*4: both penalties eps_n = eps_t (20 in the decks) divided or multiplied by 4;
  - dt*2, dt/2: 50 or 200 equal steps instead of 100 (the press keeps its fifth of the time);
  - mesh*1.5: the slab's (and a meshed die's) element counts 1.5 times in every direction.
Prints one Markdown row per run: iterations per step in developed sliding (t > 0.4), the run's
iterations (+ those of failed attempts, line-search retries / cut-backs), the mean die force Fz
and friction ratio there. One command from a built checkout (about 25 minutes on 2 cores):

    /usr/bin/python3 scripts/ironing_sensitivity.py [--decks NAME,NAME] [--jobs N] [--work DIR]
"""
import argparse
import concurrent.futures
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import ironing_predictor  # noqa: E402

DECKS = os.path.join(ROOT, "input", "stress", "ironing")
DEFAULT_DECKS = "ironing_sts_mu03_wide_smooth,ironing_stas_mu03"
MESH_COUNTS = {"nx": 18, "ny": 8, "nz": 6, "nd": 20, "ndy": 10}  # ironing.geo's defaults


def penalties(factor):
    def edit(text):
        if text.count("eps_n=20 eps_t=20") != 1:
            sys.exit("the deck's contact line has no 'eps_n=20 eps_t=20'")
        return text.replace("eps_n=20 eps_t=20", f"eps_n={20 * factor:g} eps_t={20 * factor:g}")
    return edit


def steps(count):
    def edit(text):
        if "steps 100 dt=0.01" not in text:
            sys.exit("the deck has no 'steps 100 dt=0.01'")
        return text.replace("steps 100 dt=0.01", f"steps {count} dt={1 / count:g}")
    return edit


def refined(text):
    """The mesh line with every element count 1.5 times the deck's (or ironing.geo's default);
    the die's counts nd (around, kept even) and ndy only when the die is meshed."""
    match = re.search(r'^mesh "[^"]*ironing\.geo"(.*)$', text, flags=re.M)
    if not match:
        sys.exit("the deck does not mesh ironing.geo")
    given = dict(re.findall(r"(\w+)=([\d.]+)", match.group(1)))
    counts = dict(MESH_COUNTS)
    if given.get("withDie") == "0":
        del counts["nd"], counts["ndy"]
    line = match.group(0)
    for name, default in counts.items():
        value = round(1.5 * float(given.get(name, default)))
        if name == "nd":
            value += value % 2
        line = re.sub(rf"\s{name}=[\d.]+", "", line) + f" {name}={value}"
    return text.replace(match.group(0), line)


VARIANTS = [("base", lambda text: text), ("eps/4", penalties(0.25)), ("eps*4", penalties(4)),
            ("dt*2", steps(50)), ("dt/2", steps(200)), ("mesh*1.5", refined)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--covcontact", default=os.path.join(ROOT, "build", "src", "app",
                                                             "covcontact"))
    parser.add_argument("--decks", default=DEFAULT_DECKS)
    parser.add_argument("--work", default="/tmp/ironing_sensitivity")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--limit", type=float, default=900, help="seconds per run")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    jobs = []
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for deck in args.decks.split(","):
            text = ironing_predictor.with_predictor(ironing_predictor.absolute_paths(
                open(os.path.join(DECKS, deck + ".deck")).read()))
            for label, edit in VARIANTS:
                stem = f"{deck}_{re.sub(r'[^A-Za-z0-9]', '_', label)}"
                jobs.append((deck, label, pool.submit(ironing_predictor.run, args.covcontact,
                                                      args.work, stem, edit(text), args.limit)))
    print("| deck | variant | developed | its (+discarded, retries / cut-backs) | mean Fz | "
          "Fx/Fz |")
    print("|---|---|---|---|---|---|")
    for deck, label, job in jobs:
        result = job.result()
        print(f"| `{deck}` | {label} | {ironing_predictor.cell(result)} | "
              f"{ironing_predictor.iterations_cell(result)} | "
              f"{abs(result.get('Fz_mean', float('nan'))):.3f} | "
              f"{result.get('Fx/Fz_mean', float('nan')):.4f} |")


if __name__ == "__main__":
    main()
