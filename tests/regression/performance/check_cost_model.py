"""Cheap, non-timed checks of the cost model (issue 8), run by CTest with the benchmark driver:

  analysis  the symbolic analysis runs once per sparsity-pattern change and backend, not per
            Newton iteration (work counters of a short example 6.1 run);
  search    the contact search has no all-pairs loop: its instruction count (callgrind) grows
            like the number of contact points, with exponent <= 1.15 over a 4x larger surface.

usage: check_cost_model.py analysis|search DRIVER SOURCE_DIR WORK_DIR
"""

import json
import math
import os
import re
import subprocess
import sys

# The bound on the search's growth (n log n over 10 k to 1 M points).
MAX_SEARCH_EXPONENT = 1.15
# Linear solver backends that may each analyze a pattern once (CHOLMOD, then UMFPACK when the
# frictional tangent turns unsymmetric).
BACKENDS = 2


def deck(source_dir, mesh, slide_steps):
    """Example 6.1 as the benchmark runs it (scripts/bench.py), on `mesh` (block_on_base.geo
    parameters), pressed in one step and slid by the paper's increment in `slide_steps` steps."""
    sys.path.insert(0, os.path.join(source_dir, "scripts"))
    import bench
    slide = dict(bench.PAPER_SLIDE, steps=slide_steps)
    return bench.deck_text("cost model check", mesh, slide,
                           geo=os.path.join(source_dir, "meshes", "block_on_base.geo"))


def write(path, text):
    with open(path, "w") as out:
        out.write(text)
    return path


def check_analysis(driver, source_dir, work):
    """Paper mesh, press + 8 slide steps: many iterations and pattern rebuilds."""
    path = write(os.path.join(work, "analysis.deck"),
                 deck(source_dir, dict(nx=40, ny=10, nz=1, nbx=48, nby=2), 8))
    output = subprocess.run([driver, path, "-o", os.path.join(work, "analysis.h5"), "--threads",
                             "1"], check=True, capture_output=True, text=True).stdout
    run = json.loads(output.strip().splitlines()[-1])
    print(json.dumps({k: run[k] for k in ("iterations", "factorizations", "reused_factors",
                                          "analyses", "pattern_builds", "pattern_versions")}))
    assert run["completed"], run["message"]
    assert run["pattern_builds"] > 1, "the check needs a run that rebuilds its pattern"
    assert 1 <= run["pattern_versions"] <= run["pattern_builds"]
    assert run["analyses"] <= BACKENDS * run["pattern_versions"], \
        f"{run['analyses']} analyses for {run['pattern_versions']} patterns"
    # Every iteration's tangent is factorized or solved with an earlier factor (factor_reuse.hpp).
    assert run["factorizations"] + run["reused_factors"] >= run["iterations"] > 4 * run["analyses"]


def search_instructions(driver, path, work, tag):
    """Instructions of ContactPair::prepare (all calls) and of its first call (history start)."""
    out = os.path.join(work, f"callgrind.{tag}")
    # Only the searches are instrumented (the driver's client requests): meshing and model
    # set-up run uninstrumented, which keeps the check to seconds.
    subprocess.run(["valgrind", "--tool=callgrind", "--instr-atstart=no",
                    f"--callgrind-out-file={out}",
                    driver, path, "--search"], check=True, capture_output=True)
    annotated = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                               check=True, capture_output=True, text=True).stdout
    counts = {}
    for line in annotated.splitlines():
        match = re.match(r"\s*([\d,]+)\s.*cc::contact::ContactPair::(prepare|initializeHistory)\(",
                         line)
        if match:
            counts[match.group(2)] = int(match.group(1).replace(",", ""))
    return counts["prepare"], counts["initializeHistory"]


def check_search(driver, source_dir, work):
    """Thin bodies with a fine interface; the finer mesh has 4x the contact points."""
    sizes = [(dict(nx=50, ny=1, nz=6, nbx=60, nby=1), 60 * 6 * 4),
             (dict(nx=100, ny=1, nz=12, nbx=120, nby=1), 120 * 12 * 4)]
    slides = []
    for k, (mesh, points) in enumerate(sizes):
        path = write(os.path.join(work, f"search{k}.deck"), deck(source_dir, mesh, 1))
        prepare, initial = search_instructions(driver, path, work, k)
        slides.append(prepare - initial)
        print(f"{points} points: prepare {prepare} instructions, of which {initial} in the "
              f"first search")
    exponent = math.log(slides[1] / slides[0]) / math.log(sizes[1][1] / sizes[0][1])
    print(f"search after a slide: exponent {exponent:.3f} (bound {MAX_SEARCH_EXPONENT})")
    assert exponent <= MAX_SEARCH_EXPONENT, f"search grows like n^{exponent:.2f}"


def main():
    check, driver, source_dir, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    {"analysis": check_analysis, "search": check_search}[check](driver, source_dir, work)


if __name__ == "__main__":
    main()
