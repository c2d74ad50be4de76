#!/usr/bin/python3
"""Solver survey on real tangents (issue 13).

1. Dumps: runs benchmark decks with `covcontact run --dump-tangent STEP:ITER` (stick: the first
   sliding step, slip: the last one) and stops each run once its dumps are written.
2. Solves every dump with every solver configuration, each in its own process
   (`covcontact solve-dump DIR --solver S`), and records wall time by phase, the process's
   peak resident memory (wait4), Krylov iterations and the achieved relative residual.
3. Writes docs/performance/solvers.md (table), solvers.json (raw) and solvers.png (time per
   solve against equations, log-log, with fitted slopes).

The matrices stay out of git (they are hundreds of MiB); the table and plot are committed.

    /usr/bin/python3 scripts/solver_survey.py --sizes 11k,20k,57k
    /usr/bin/python3 scripts/solver_survey.py --report       # redraw from solvers.json
"""
import argparse
import json
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
COVCONTACT = ROOT / "build" / "src" / "app" / "covcontact"
DECKS = ROOT / "input" / "performance"
OUT = ROOT / "docs" / "performance"
SOLVERS = ["cholmod", "umfpack", "mumps", "superlu_dist", "amg", "gamg"]
# Scaling decks: step 1 presses, steps 2-5 slide (2: stick/partial slip, 5: nearly full slip).
STATES = {"stick": "2:2", "slip": "5:2"}
# Fitted slopes use the systems of at least this many equations.
SLOPE_FROM_EQUATIONS = 40000


def load_average():
    return os.getloadavg()[0]


def make_dumps(size, work, timeout, reuse=False, run_solver=None):
    """Runs scaling_<size>.deck until the stick and slip tangents are written (reuse: take the
    dumps that exist, run nothing; run_solver: the run's --solver, e.g. gamg to reach the
    1.2 M dumps sooner; it changes the Newton path only within the solve tolerance)."""
    deck = DECKS / f"scaling_{size}.deck"
    results = work / f"scaling_{size}.h5"
    wanted = {state: work / f"scaling_{size}_tangent_{it.replace(':', '_')}"
              for state, it in STATES.items()}
    if reuse or all((d / "info.txt").exists() for d in wanted.values()):
        return {s: d for s, d in wanted.items() if (d / "info.txt").exists()}
    args = [str(COVCONTACT), "run", str(deck), "-q", "--threads", "1", "-o", str(results)]
    for it in STATES.values():
        args += ["--dump-tangent", it]
    if run_solver:
        args += ["--solver", run_solver]
    start = time.time()
    process = subprocess.Popen(args, cwd=deck.parent, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    while process.poll() is None:
        if all((d / "info.txt").exists() for d in wanted.values()):
            process.send_signal(signal.SIGTERM)  # stops after the current iteration
            break
        if time.time() - start > timeout:
            process.kill()
            break
        time.sleep(1)
    process.wait()
    return {s: d for s, d in wanted.items() if (d / "info.txt").exists()}


def solve(dump, solver, rtol, timeout):
    args = [str(COVCONTACT), "solve-dump", str(dump), "--solver", solver, "--rtol", str(rtol)]
    start = time.time()
    process = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               env=dict(os.environ, OMP_NUM_THREADS="1"))
    try:
        out, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        return {"solver": solver, "error": f"timeout {timeout} s"}
    wall = time.time() - start
    # Peak RSS of this child alone: RUSAGE_CHILDREN is a maximum over all children so far.
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    line = next((l for l in out.decode().splitlines() if l.startswith("{")), None)
    record = json.loads(line) if line else {"solver": solver, "error": err.decode()[-300:]}
    record["process_wall_s"] = wall
    record["children_peak_rss_mib"] = usage.ru_maxrss / 1024
    record["load_average"] = load_average()
    return record


def solve_measured(dump, solver, rtol, timeout):
    """solve() in a wrapper process of its own, so that ru_maxrss is this solve's peak."""
    code = (f"import sys, json; sys.path.insert(0, {str(Path(__file__).parent)!r}); "
            f"import solver_survey as s; "
            f"print(json.dumps(s.solve({str(dump)!r}, {solver!r}, {rtol}, {timeout})))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    try:
        return json.loads(out.stdout.strip().splitlines()[-1])
    except (IndexError, json.JSONDecodeError):
        return {"solver": solver, "error": out.stderr[-300:]}


def cpu_total(r):
    """CPU seconds of analysis + factorization/setup + solve (wall seconds for records that
    predate the CPU columns)."""
    if "cpu_factorize_s" in r:
        return r["cpu_factorize_s"] + r["cpu_solve_s"]
    return r["analysis_s"] + r["factor_s"] + r["solve_s"]


def report(records):
    lines = ["| equations | state | solver | backend | CPU factor/setup s | CPU solve s | "
             "CPU total s | wall total s | Krylov it. | rel. residual | peak RSS MiB | load |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(records, key=lambda r: (r.get("equations", 0), r.get("state", ""),
                                             SOLVERS.index(r["solver"]))):
        if r.get("error"):
            lines.append(f"| {r.get('equations', '')} | {r.get('state', '')} | {r['solver']} | "
                         f"failed: {r['error'][:60]} | | | | | | | | |")
            continue
        cpu = (f"{r['cpu_factorize_s']:.2f} | {r['cpu_solve_s']:.2f}" if "cpu_factorize_s" in r
               else "| ")
        lines.append(
            f"| {r['equations']} | {r['state']} | {r['solver']} | "
            f"{r['backend']}{' (fallback)' if r['fallback'] else ''} | {cpu} | "
            f"{cpu_total(r):.2f} | {r['analysis_s'] + r['factor_s'] + r['solve_s']:.2f} | "
            f"{r['krylov_iterations']} | {r['relative_residual']:.1e} | "
            f"{r['children_peak_rss_mib']:.0f} | {r['load_average']:.1f} |")
    return "\n".join(lines)


def plot(records, path):
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    slopes = {}
    for index, solver in enumerate(SOLVERS):
        color = f"C{index}"
        for state, marker, line in (("stick", "o", "-"), ("slip", "s", "--")):
            pts = sorted((r["equations"], cpu_total(r)) for r in records
                         if r["solver"] == solver and r.get("state") == state and not r.get("error"))
            if not pts:
                continue
            n, t = np.array(pts).T
            label = f"{solver} {state}"
            # The slope over the sizes where the work grows, not the fixed costs of the small
            # ones (below ~40 k equations every solver takes a fraction of a second).
            large = n >= SLOPE_FROM_EQUATIONS
            if large.sum() >= 2:
                slope = np.polyfit(np.log(n[large]), np.log(t[large]), 1)[0]
                slopes[label] = slope
                label += f" (slope {slope:.2f})"
            ax.loglog(n, t, marker=marker, linestyle=line, color=color, label=label)
    ax.set_xlabel("equations")
    ax.set_ylabel("CPU s: analysis + factorization/setup + solve (one thread)")
    ax.set_title("One Newton system, dumped tangents of example 6.1 scaled")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return slopes


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default="11k,20k,57k")
    parser.add_argument("--solvers", default=",".join(SOLVERS))
    parser.add_argument("--rtol", type=float, default=1e-8)
    parser.add_argument("--work", default="/tmp/covcontact_solver_survey")
    parser.add_argument("--timeout", type=float, default=900)
    parser.add_argument("--run-solver", help="--solver of the runs that write the dumps")
    parser.add_argument("--report", action="store_true", help="only redraw from solvers.json")
    parser.add_argument("--reuse-dumps", action="store_true",
                        help="solve the dumps that exist, run no deck")
    args = parser.parse_args()
    raw = OUT / "solvers.json"
    records = json.loads(raw.read_text()) if raw.exists() else []
    if not args.report:
        work = Path(args.work)
        work.mkdir(parents=True, exist_ok=True)
        for size in args.sizes.split(","):
            dumps = make_dumps(size, work, args.timeout, args.reuse_dumps,
                               args.run_solver)
            for state, dump in dumps.items():
                for solver in args.solvers.split(","):
                    record = solve_measured(dump, solver, args.rtol, args.timeout)
                    record.update(size=size, state=state)
                    records = [r for r in records if not (r.get("size") == size and
                               r.get("state") == state and r["solver"] == solver)]
                    records.append(record)
                    print(json.dumps(record), flush=True)
                    raw.write_text(json.dumps(records, indent=1))
    table = report(records)
    slopes = plot(records, OUT / "solvers.png")
    (OUT / "solvers_table.md").write_text(
        "<!-- generated by scripts/solver_survey.py; see solvers.md -->\n" + table + "\n\n" +
        f"Fitted slopes (CPU time ~ equations^slope, from {SLOPE_FROM_EQUATIONS} equations): " +
        ", ".join(f"{k} {v:.2f}" for k, v in sorted(slopes.items())) + "\n")
    print(table)


if __name__ == "__main__":
    main()
