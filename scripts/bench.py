#!/usr/bin/python3
"""Performance benchmark of CovContact (issue 8), one command from a clean checkout:

    scripts/install-deps.sh && cmake -S . -B build -G Ninja && cmake --build build
    /usr/bin/python3 scripts/bench.py

It needs the README's build (build/src/app/covcontact and the benchmark driver
build/tests/regression/performance/covcontact_bench, both built by `cmake --build build`) and
CalculiX (`calculix-ccx`, installed by scripts/install-deps.sh). It runs:

  scaling    example 6.1 (block on base, STS, friction, press + slide) refined from ~10 k to
             ~1 M dofs (input/performance/*.deck), one thread (--threads), until a run
             exceeds the time or memory limit; per run the cost split, iterations, peak RSS;
             runs of other sizes already in results.json are kept (--sizes completes a sweep);
  orderings  CHOLMOD with AMD, METIS and NESDIS on each size's first tangent;
  blas       the same factorizations with OpenBLAS (serial) and the reference BLAS;
  search     the contact search alone on surfaces with 10 k to 1 M contact points;
  calculix   CalculiX 2.20 and `covcontact run` on the same mesh and loading, side by side;
  memory     the memory target's run: 232 k dofs with the direct solvers (`--solver cholmod`:
             CHOLMOD while sticking, UMFPACK after), peak RSS against the largest factor + mesh
             (the scaling runs there use the deck's solver=auto, which solves iteratively);

and writes docs/performance/results.json (every number measured), tables.md and the log-log
plots. `--only PART[,PART]` runs some parts, `--report` only redraws tables and plots from
results.json, `--write-decks` regenerates input/performance/. `--threads-study` runs only the
1 vs 2 threads comparison (THREADS_STUDY_SIZES), which needs an otherwise idle machine.
"""

import argparse
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import bench_calculix  # noqa: E402
import bench_report  # noqa: E402
import bench_runs  # noqa: E402

DECK_DIR = os.path.join(ROOT, "input", "performance")
DOCS_DIR = os.path.join(ROOT, "docs", "performance")

# Example 6.1 as in input/paper/sliding_block_6_1a.deck (paper section 6.1).
LOADING = dict(young=2.1e4, poisson=0.3, eps_n=2.1e6, eps_t=2.1e6, mu=0.3, press=-7e-3,
               slide=0.025, slide_steps=100)

# The paper's mesh (block 40 x 10 x 1, base 48 x 2 x 1) refined by `r` in x and y and by
# `nz` through the thickness; named by their approximate number of dofs.
SCALING_SIZES = [
    ("11k", dict(nx=60, ny=15, nz=2, nbx=72, nby=3)),
    ("20k", dict(nx=80, ny=20, nz=2, nbx=96, nby=4)),
    ("57k", dict(nx=120, ny=30, nz=3, nbx=144, nby=6)),
    ("125k", dict(nx=160, ny=40, nz=4, nbx=192, nby=8)),
    ("232k", dict(nx=200, ny=50, nz=5, nbx=240, nby=10)),
    ("388k", dict(nx=240, ny=60, nz=6, nbx=288, nby=12)),
    ("600k", dict(nx=280, ny=70, nz=7, nbx=336, nby=14)),
    ("880k", dict(nx=320, ny=80, nz=8, nbx=384, nby=16)),
    ("1.2M", dict(nx=360, ny=90, nz=9, nbx=432, nby=18)),
]
# The scaling decks press, then slide by 4 x 2.5e-3 (stick, partial slip, nearly full slip at
# u = 1e-2; the paper's onset is 7.5e-3), with the line search on from the start so that no
# step first fails without it: the cost per Newton iteration is what scales, and this keeps the
# large sizes within the time limit.
SCALING_SLIDE = dict(steps=4, increment=2.5e-3, line_search=True)
PAPER_SLIDE = dict(steps=LOADING["slide_steps"], increment=LOADING["slide"] / LOADING["slide_steps"],
                   line_search=False)

# Contact-search series: thin bodies (one element layer) with a fine contact surface; the
# number of contact points (4 per base-top face) runs from ~10 k to ~1 M.
SEARCH_SIZES = [
    ("10k", dict(nx=100, ny=1, nz=20, nbx=120, nby=1)),
    ("40k", dict(nx=200, ny=1, nz=40, nbx=240, nby=1)),
    ("160k", dict(nx=400, ny=1, nz=80, nbx=480, nby=1)),
    ("360k", dict(nx=600, ny=1, nz=120, nbx=720, nby=1)),
    ("1M", dict(nx=1000, ny=1, nz=200, nbx=1200, nby=1)),
]

# CalculiX comparison: the paper's mesh with the paper's loading, and one refinement.
CALCULIX_SIZES = [
    ("paper", dict(nx=40, ny=10, nz=1, nbx=48, nby=2)),
    ("11k", dict(SCALING_SIZES[0][1])),
]

# BLAS libraries compared for the factorization (Debian's alternatives; the loader takes
# libblas.so.3 and liblapack.so.3 from the first directory that has them).
BLAS_VARIANTS = {
    "openblas-serial": "/usr/lib/x86_64-linux-gnu/openblas-serial",
    "reference": "/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack",
}
BLAS_SIZES = ["57k", "125k"]
# The 1 vs 2 threads comparison (--threads-study): sizes large enough that assembly dominates
# thread start-up, small enough to rerun in a few minutes on an idle machine (~3 min).
THREADS_STUDY_SIZES = ["20k", "57k"]
# The memory target's size (issue 8: peak RSS <= 1.5 x (factor + mesh) at 232 k dofs).
MEMORY_SIZE = "232k"

LIMIT_SECONDS = 15 * 60
LIMIT_BYTES = 24 * 2**30


def deck_text(title, mesh, slide, geo="../../meshes/block_on_base.geo"):
    """The example 6.1 deck on the mesh `mesh` (block_on_base.geo parameters); `geo` is the
    path of the .geo as the deck sees it (relative to the deck's directory)."""
    parameters = " ".join(f"{k}={v}" for k, v in mesh.items())
    search = " line_search=yes" if slide["line_search"] else ""
    return f"""\
# {title}
# Example 6.1 (Konyukhov & Schweizerhof 2005) as in input/paper/sliding_block_6_1a.deck, on a
# refined mesh: press v = {LOADING['press']:g} in one step, then slide in {slide['steps']} steps of
# u = {slide['increment']:g}. Written by scripts/bench.py --write-decks (performance, issue 8).
title "{title}"
mesh "{geo}" {parameters}
material elastic svk E={LOADING['young']:g} nu={LOADING['poisson']:g}
elements block hex8 material=elastic
elements base hex8 material=elastic
fix base_bottom all
fix block_front uz
fix block_back uz
fix base_front uz
fix base_back uz
prescribe block_top uy "{LOADING['press']:g}*min(t,1)" ux "{slide['increment']:g}*max(t-1,0)"
contact sts master=block_bottom slave=base_top eps_n={LOADING['eps_n']:g} eps_t={LOADING['eps_t']:g} mu={LOADING['mu']:g} points=2 name=interface
output fields=displacement,reaction,contact
solve
  steps 1 dt=1{search}
  steps {slide['steps']} dt=1{search}
end
"""


def deck_path(series, name):
    return os.path.join(DECK_DIR, f"{series}_{name}.deck")


def write_decks():
    os.makedirs(DECK_DIR, exist_ok=True)
    for name, mesh in SCALING_SIZES:
        with open(deck_path("scaling", name), "w") as out:
            out.write(deck_text(f"Example 6.1 scaled, {name} dofs", mesh, SCALING_SLIDE))
    for name, mesh in SEARCH_SIZES:
        with open(deck_path("search", name), "w") as out:
            out.write(deck_text(f"Example 6.1 contact-search series, {name} points", mesh,
                                SCALING_SLIDE))
    for name, mesh in CALCULIX_SIZES:
        with open(deck_path("calculix", name), "w") as out:
            out.write(deck_text(f"Example 6.1 for the CalculiX comparison, mesh {name}", mesh,
                                PAPER_SLIDE))
        bench_calculix.write_deck(os.path.join(DECK_DIR, "calculix", f"{name}.inp"), mesh,
                                  LOADING)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory")
    parser.add_argument("--only", default="scaling,orderings,blas,search,calculix,memory",
                        help="parts to run (comma separated)")
    parser.add_argument("--sizes", help="scaling sizes to run (comma separated names)")
    parser.add_argument("--search-sizes", default=",".join(n for n, _ in SEARCH_SIZES),
                        help="sizes of the contact-search series (comma separated names)")
    parser.add_argument("--calculix-meshes", default=",".join(n for n, _ in CALCULIX_SIZES),
                        help="meshes of the CalculiX comparison (comma separated names)")
    parser.add_argument("--threads", default="1", help="thread counts of the scaling runs")
    parser.add_argument("--threads-study", action="store_true",
                        help="only the 1 vs 2 threads runs (THREADS_STUDY_SIZES; a few minutes "
                             "on an idle machine)")
    parser.add_argument("--quick", action="store_true",
                        help="smallest size of each part only (a check that everything runs)")
    parser.add_argument("--report", action="store_true", help="only redraw from results.json")
    parser.add_argument("--write-decks", action="store_true", help="regenerate the decks")
    parser.add_argument("--docs", default=DOCS_DIR, help="where results.json, tables, plots go")
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "bench"),
                        help="scratch directory for results files")
    args = parser.parse_args()
    if args.write_decks:
        write_decks()
        return
    results_path = os.path.join(args.docs, "results.json")
    results = {}
    if os.path.exists(results_path):
        with open(results_path) as stream:
            results = json.load(stream)
    if not args.report:
        runner = bench_runs.Runner(args.build, args.work, LIMIT_SECONDS, LIMIT_BYTES)
        parts = args.only.split(",")
        sizes = [s for s in SCALING_SIZES if not args.sizes or s[0] in args.sizes.split(",")]
        search_sizes = [c for c in SEARCH_SIZES if c[0] in args.search_sizes.split(",")]
        calculix_sizes = [c for c in CALCULIX_SIZES if c[0] in args.calculix_meshes.split(",")]
        if args.quick:
            sizes, search_sizes, calculix_sizes = sizes[:1], SEARCH_SIZES[:1], CALCULIX_SIZES[:1]
        threads = [int(t) for t in args.threads.split(",")]
        if args.threads_study:
            parts = []
            results["threads_study"] = runner.scaling(
                [(n, deck_path("scaling", n)) for n in THREADS_STUDY_SIZES], [1, 2])
            save(results, results_path)
        if "scaling" in parts:
            measured = runner.scaling([(n, deck_path("scaling", n)) for n, _ in sizes], threads)
            results["scaling"] = merge_scaling(results.get("scaling"), measured)
            save(results, results_path)
        if "calculix" in parts:
            results["calculix"] = runner.calculix(
                [(n, deck_path("calculix", n), os.path.join(DECK_DIR, "calculix", f"{n}.inp"))
                 for n, _ in calculix_sizes], LOADING)
            save(results, results_path)
        if "orderings" in parts:
            results["orderings"] = runner.series(
                [(n, deck_path("scaling", n)) for n, _ in sizes], "--orderings")
            save(results, results_path)
        if "blas" in parts:
            results["blas"] = runner.blas(
                [(n, deck_path("scaling", n)) for n in BLAS_SIZES[:1 if args.quick else None]],
                BLAS_VARIANTS)
            save(results, results_path)
        if "memory" in parts:
            results["memory"] = runner.memory(MEMORY_SIZE, deck_path("scaling", MEMORY_SIZE))
            save(results, results_path)
        if "search" in parts:
            results["search"] = runner.series(
                [(n, deck_path("search", n)) for n, _ in search_sizes], "--search")
            save(results, results_path)
    bench_report.write(results, args.docs, LOADING)


def merge_scaling(previous, measured):
    """The new runs, plus the earlier runs of sizes and thread counts not run again (so that a
    sweep can be completed size by size)."""
    if not previous:
        return measured
    def key(run):
        return run["size"], run["records"][0]["threads"] if run["records"] else None
    again = {key(run) for run in measured["runs"]}
    kept = [run for run in previous["runs"] if key(run) not in again]
    return {"runs": kept + measured["runs"], "stopped": measured["stopped"]}


def save(results, path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as out:
        json.dump(results, out, indent=1)


if __name__ == "__main__":
    main()
