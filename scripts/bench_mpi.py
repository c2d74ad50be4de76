#!/usr/bin/python3
"""Strong scaling of runs on several processes (issue 17): the scaling decks of scripts/bench.py
(example 6.1 refined, input/performance/scaling_*.deck: press + 4 sliding steps) on 1 and on 2
processes with the same linear solver (MUMPS, distributed LU), and on 1 process with the default
serial solver for reference. Per run it reads the `cost:` line of `covcontact run --cost`: CPU and
peak memory per process, the time of element assembly, contact (search + points) and the linear
solve per process, and the bytes moved between processes per Newton iteration.

    /usr/bin/python3 scripts/bench_mpi.py [--sizes 57k,125k] [--build build]

Writes docs/performance/distributed.json (every number) and prints the table that
docs/performance/distributed.md quotes. The machine's load average is recorded with each run:
on a shared machine compare CPU seconds, and wall ratios only between runs made back to back.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(command, timeout):
    start = time.monotonic()
    load = os.getloadavg()[0]
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"command": " ".join(command), "timed_out": timeout, "load_before": load}
    wall = time.monotonic() - start
    cost = [line for line in result.stdout.splitlines() if line.startswith("cost: ")]
    record = {"command": " ".join(command), "exit_code": result.returncode, "wall_s": wall,
              "load_before": load, "load_after": os.getloadavg()[0]}
    if cost:
        record.update(json.loads(cost[-1][len("cost: "):]))
    else:
        record["stderr"] = result.stderr[-2000:]
    return record


def configurations(args, deck, work):
    covcontact = os.path.join(args.build, "src", "app", "covcontact")
    mpirun = [shutil.which("mpirun"), "--allow-run-as-root", "--oversubscribe"]
    for name, prefix, solver in (("serial_default", [], None),
                                 ("mumps_np1", [], "mumps"),
                                 ("mumps_np2", mpirun + ["-np", "2"], "mumps")):
        results = os.path.join(work, f"{os.path.basename(deck)[:-5]}_{name}.h5")
        command = prefix + [covcontact, "run", deck, "-o", results, "-q", "--cost", "--threads", "1"]
        if solver:
            command += ["--solver", solver]
        yield name, command


def speedups(one, two):
    """Ratios 1 process / 2 processes of the slowest process's time per part."""
    ratio = {}
    for part in ("elements_s", "contact_s", "linear_solve_s"):
        if part in one and part in two:
            ratio[part] = max(one[part]) / max(max(two[part]), 1e-12)
    if "wall_s" in one and "wall_s" in two:
        ratio["wall"] = one["wall_s"] / two["wall_s"]
        ratio["cpu_per_process"] = max(one["cpu_s"]) / max(two["cpu_s"])
    return ratio


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--sizes", default="57k,125k", help="scaling deck sizes (comma separated)")
    parser.add_argument("--timeout", type=float, default=1800, help="seconds per run")
    parser.add_argument("--runs", default="serial_default,mumps_np1,mumps_np2",
                        help="which of the three runs per size (comma separated)")
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "performance",
                                                         "distributed.json"))
    args = parser.parse_args()
    work = os.path.join(args.build, "bench_mpi")
    os.makedirs(work, exist_ok=True)
    previous = {}
    if os.path.exists(args.output):
        with open(args.output) as stream:
            previous = json.load(stream)
    results = previous.get("sizes", {})
    for size in args.sizes.split(","):
        deck = os.path.join(ROOT, "input", "performance", f"scaling_{size}.deck")
        runs = {}
        for name, command in configurations(args, deck, work):
            if name not in args.runs.split(","):
                continue
            print(f"{size} {name}: {' '.join(command)}", file=sys.stderr, flush=True)
            runs[name] = run(command, args.timeout)
        if "mumps_np1" in runs and "mumps_np2" in runs:
            runs["speedup_mumps_np1_over_np2"] = speedups(runs["mumps_np1"], runs["mumps_np2"])
        results[size] = runs
        with open(args.output, "w") as stream:
            json.dump({"sizes": results}, stream, indent=1)
    print("| size | equations | run | Newton its | wall s | CPU s per process | peak RSS MiB per "
          "process | elements s | contact s | linear solve s | bytes per iteration |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for size, runs in results.items():
        for name in ("serial_default", "mumps_np1", "mumps_np2"):
            if name not in runs:
                continue  # not asked for (--runs)
            r = runs[name]
            if "cpu_s" not in r:
                print(f"| {size} | | {name} | failed or timed out | | | | | | | |")
                continue
            moved = r["bytes_per_iteration"]
            print(f"| {size} | {r['equations']} | {name} | {r['iterations']} | {r['wall_s']:.1f} | "
                  f"{', '.join(f'{v:.1f}' for v in r['cpu_s'])} | "
                  f"{', '.join(f'{v:.0f}' for v in r['peak_rss_mib'])} | "
                  f"{max(r['elements_s']):.2f} | {max(r['contact_s']):.2f} | "
                  f"{max(r['linear_solve_s']):.2f} | "
                  f"{sum(moved.values()) / 1e6:.2f} MB (force {moved['force_sums'] / 1e6:.2f}, "
                  f"matrix {moved['matrix_entries'] / 1e6:.2f}, solution "
                  f"{moved['solution'] / 1e6:.2f}) |")
        ratio = runs.get("speedup_mumps_np1_over_np2", {})
        if ratio:
            print(f"| {size} | | speed-up 1 -> 2 processes (MUMPS) | | "
                  + " | ".join(f"{k} {v:.2f}x" for k, v in ratio.items()) + " | | | | | |")


if __name__ == "__main__":
    main()
