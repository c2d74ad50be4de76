#!/usr/bin/python3
"""Every target of issue 13 (large models on one machine, small-model overheads), one command
from a clean checkout:

    scripts/install-deps.sh && cmake -S . -B build -G Ninja && cmake --build build
    /usr/bin/python3 scripts/bench_targets.py [--only PART,...] [--build build]
        [--output docs/performance/targets.json]

Parts, in the order they run (about an hour on an idle 2-core machine, most of it the two
1.2 M runs):

  calculix  example 6.1 on the paper mesh, CovContact and CalculiX 2.20 one after the other, one
            thread each, twice (scripts/bench_runs.py): wall-time ratio >= 25;
  die       the 6 k-unknown die dragged across a slab with friction
            (input/stress/ironing/ironing_sts_mu03_equal.deck), one thread, twice: CPU time per
            Newton iteration <= 30 ms;
  thin      the scaling decks (example 6.1 refined) of 388 k and 1.2 M dofs, `mpirun -np 2`,
            `solver=auto`, one thread per process (scripts/bench_mpi.py): <= 5 and <= 15 min
            within 24 GiB;
  bulk      the 3D bulk geometry (input/performance/bulk_79k.deck refined to 341 k and 1.2 M
            dofs), the same way: <= 5 and <= 15 min within 24 GiB;
  threads   element assembly + contact kernel from 1 to 2 threads (scripts/bench.py's threads
            study, 20 k and 57 k dofs): >= 1.7x;
  search    the contact search alone, 10 k to 1 M points: fitted exponent <= 1.15;
  memory    232 k dofs with the direct solvers: peak RSS <= 1.5 x (factor + mesh).

From the 1.2 M runs it also reads the share of the wall time outside the linear solve (target
<= 25 %). The log-log plot of time per iteration against size per solver is
scripts/solver_survey.py's (docs/performance/solvers.png); it is not redone here.

It prints one table, target by target, with the measured numbers and met / missed, and writes
every run's record to --output. Timed runs are only comparable on a quiet machine: the load
average before and after each run is recorded and printed.
"""
import argparse
import json
import os
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

import bench  # noqa: E402
import bench_mpi  # noqa: E402
import bench_report  # noqa: E402
import bench_runs  # noqa: E402

PARTS = ["calculix", "die", "thin", "bulk", "threads", "search", "memory"]
DIE_DECK = os.path.join(ROOT, "input", "stress", "ironing", "ironing_sts_mu03_equal.deck")
PERFORMANCE = os.path.join(ROOT, "input", "performance")
# Size name -> (deck, wall-time limit in seconds).
LARGE = {"thin": [("388k", "scaling_388k.deck", 5 * 60), ("1.2M", "scaling_1.2M.deck", 15 * 60)],
         "bulk": [("bulk341k", "bulk_79k.deck", 5 * 60), ("bulk1.2M", "bulk_79k.deck", 15 * 60)]}
MEMORY_LIMIT_MIB = 24 * 1024
NON_SOLVE_SHARE = 0.25


def calculix(runner, rounds=2):
    """Example 6.1 on the paper mesh against CalculiX, `rounds` times back to back."""
    case = ("paper", bench.deck_path("calculix", "paper"),
            os.path.join(PERFORMANCE, "calculix", "paper.inp"))
    return [runner.calculix([case], bench.LOADING)[0] for _ in range(rounds)]


def die(build, work, rounds=2):
    """The die model on one thread: `covcontact run --cost`, CPU and wall per Newton iteration."""
    covcontact = os.path.join(build, "src", "app", "covcontact")
    records = []
    for round_ in range(rounds):
        command = [covcontact, "run", DIE_DECK, "-o", os.path.join(work, f"die{round_}.h5"), "-q",
                   "--cost", "--threads", "1"]
        print(f"bench_targets: {' '.join(command)}", file=sys.stderr, flush=True)
        records.append(bench_mpi.run(command, timeout=1800))
    return records


def large(build, work, family):
    """The 388 k / 1.2 M runs of one geometry on two processes with solver=auto."""
    covcontact = os.path.join(build, "src", "app", "covcontact")
    mpirun = [shutil.which("mpirun") or "mpirun", "--allow-run-as-root", "-np", "2"]
    records = {}
    for size, deck_name, _ in LARGE[family]:
        deck = os.path.join(PERFORMANCE, deck_name)
        if size in bench_mpi.BULK_SLAB:
            deck = bench_mpi.deck_copy(deck, work, size=size)
        command = mpirun + [covcontact, "run", deck, "-o", os.path.join(work, f"{size}.h5"), "-q",
                            "--cost", "--threads", "1", "--solver", "auto"]
        print(f"bench_targets: {' '.join(command)}", file=sys.stderr, flush=True)
        records[size] = bench_mpi.run(command, timeout=3 * 3600)
    return records


def verdict(met):
    return "met" if met else "**missed**"


def load_of(record):
    before, after = record.get("load_before"), record.get("load_after")
    return f"load {before:.1f}-{after:.1f}" if after is not None else f"load {before:.1f}"


def calculix_lines(rounds):
    lines = []
    for k, c in enumerate(rounds, 1):
        ccx, ours, extrapolating = c["calculix"], c["covcontact"], c["covcontact_extrapolate"]
        ratio = ccx["wall"] / ours["wall"]
        lines.append(
            f"| 6.1, paper mesh, >= 25x CalculiX (wall, one thread), round {k} | CalculiX "
            f"{ccx['wall']:.1f} s ({ccx.get('iterations', '?')} its), CovContact "
            f"{ours['wall']:.2f} s ({ours['iterations']} its): **{ratio:.1f}x** (CPU "
            f"{ccx['cpu'] / ours['cpu']:.1f}x); `predictor=extrapolate` {extrapolating['wall']:.2f} s "
            f"({extrapolating['iterations']} its): {ccx['wall'] / extrapolating['wall']:.1f}x; "
            f"{load_of(ccx)} | {verdict(ratio >= 25)} |")
    return lines


def die_lines(records):
    lines = []
    for k, r in enumerate(records, 1):
        if "cpu_s" not in r:
            lines.append(f"| die model <= 30 ms per iteration, round {k} | failed: "
                         f"{r.get('stderr', r.get('timed_out', ''))[-200:]} | **missed** |")
            continue
        per_iteration = 1000 * r["cpu_s"][0] / r["iterations"]
        phases = r["linear_phases_rank0"]
        lines.append(
            f"| die model (4 212 equations) <= 30 ms CPU per Newton iteration, round {k} | "
            f"**{per_iteration:.1f} ms** ({r['iterations']} its, {r['cpu_s'][0]:.1f} CPU s; "
            f"elements {r['elements_s'][0]:.1f} s, contact {r['contact_s'][0]:.1f} s, linear "
            f"solve {r['linear_solve_s'][0]:.1f} s: {phases['factorizations']} factorizations, "
            f"{phases['krylov_iterations']} Krylov its on kept factors); {load_of(r)} | "
            f"{verdict(per_iteration <= 30)} |")
    return lines


def large_lines(family, records):
    lines = []
    for size, _, limit in LARGE[family]:
        r = records.get(size, {})
        label = (f"{family} {size.removeprefix(family)}, 2 processes, solver=auto, "
                 f"<= {limit // 60} min in 24 GiB")
        if "cpu_s" not in r or r.get("exit_code"):
            lines.append(f"| {label} | failed or timed out: "
                         f"{str(r.get('stderr', r.get('timed_out', '')))[-200:]} | **missed** |")
            continue
        memory = sum(r["peak_rss_mib"])
        # auto's switch from GAMG to BoomerAMG: the solve that decided it.
        notes = "; ".join(note.split(": a new GAMG")[0] + " -> BoomerAMG"
                          for note in r.get("solver_notes", [])[:1])
        met = r["wall_s"] <= limit and memory <= MEMORY_LIMIT_MIB
        lines.append(f"| {label} | **{r['wall_s']:.1f} s = {r['wall_s'] / 60:.1f} min**, "
                     f"{r['equations']} equations, {r['iterations']} Newton its, "
                     f"{memory / 1024:.1f} GiB in all; {notes or 'no switch of preconditioner'}; "
                     f"{load_of(r)} | {verdict(met)} |")
        if size.endswith("1.2M"):
            outside = 1 - max(r["linear_solve_s"]) / r["wall_s"]
            lines.append(f"| {family} 1.2 M: every part but the linear solve <= 25 % | "
                         f"{100 * outside:.1f} % of the wall time (elements "
                         f"{max(r['elements_s']):.0f} s, contact {max(r['contact_s']):.0f} s) | "
                         f"{verdict(outside <= NON_SOLVE_SHARE)} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--only", default=",".join(PARTS), help="parts to run (comma separated)")
    parser.add_argument("--output", default=os.path.join(ROOT, "build", "bench_targets",
                                                         "targets.json"),
                        help="every run's record (JSON); parts not run are kept from it")
    parser.add_argument("--report", action="store_true", help="only print the table of --output")
    args = parser.parse_args()
    build = os.path.abspath(args.build)
    work = os.path.join(build, "bench_targets")
    os.makedirs(work, exist_ok=True)
    results = {}
    if os.path.exists(args.output):
        with open(args.output) as stream:
            results = json.load(stream)
    parts = [] if args.report else args.only.split(",")
    unknown = set(parts) - set(PARTS)
    if unknown:
        sys.exit(f"bench_targets: unknown part(s) {', '.join(sorted(unknown))}; "
                 f"parts: {', '.join(PARTS)}")
    runner = bench_runs.Runner(build, work, bench.LIMIT_SECONDS, bench.LIMIT_BYTES) if parts else None

    def save():
        os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
        with open(args.output, "w") as stream:
            json.dump(results, stream, indent=1)

    for part in PARTS:
        if part not in parts:
            continue
        if part == "calculix":
            results[part] = calculix(runner)
        elif part == "die":
            results[part] = die(build, work)
        elif part in LARGE:
            results[part] = large(build, work, part)
        elif part == "threads":
            results[part] = runner.scaling(
                [(n, bench.deck_path("scaling", n)) for n in bench.THREADS_STUDY_SIZES], [1, 2])
        elif part == "search":
            results[part] = runner.series(
                [(n, bench.deck_path("search", n)) for n, _ in bench.SEARCH_SIZES], "--search")
        elif part == "memory":
            results[part] = runner.memory(bench.MEMORY_SIZE,
                                          bench.deck_path("scaling", bench.MEMORY_SIZE))
        save()

    lines = ["| target | measured | met? |", "|---|---|---|"]
    if "calculix" in results:
        lines += calculix_lines(results["calculix"])
    if "die" in results:
        lines += die_lines(results["die"])
    for family in LARGE:
        if family in results:
            lines += large_lines(family, results[family])
    if "threads" in results:
        study = results["threads"]
        lines += bench_report.speedup_lines(bench_report.completed_runs(study, 1),
                                            bench_report.completed_runs(study, 2))
    if "search" in results:
        exponent = bench_report.search_exponent(results["search"])
        if exponent is not None:
            lines.append(f"| contact search exponent <= 1.15 (10 k to 1 M points) | "
                         f"{exponent:.2f}, points {bench_report.search_points(results['search'])}"
                         f" | {verdict(exponent <= 1.15)} |")
    if "memory" in results:
        r = results["memory"]
        record = (r.get("records") or [{}])[0]
        if record.get("factor_bytes"):
            ratio = r["peak_rss_bytes"] / (record["factor_bytes"] + record["mesh_bytes"])
            lines.append(f"| peak RSS <= 1.5 x (factor + mesh) at {record['dofs']} dofs "
                         f"(`--solver cholmod`) | {ratio:.2f}x | {verdict(ratio <= 1.5)} |")
        else:
            lines.append(f"| peak RSS <= 1.5 x (factor + mesh) at 232 k dofs | the run stopped "
                         f"({r.get('stopped') or r.get('exit_code')}) | **missed** |")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
