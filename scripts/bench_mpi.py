#!/usr/bin/python3
"""Strong scaling of runs on several processes (issue 17): the scaling decks of scripts/bench.py
(example 6.1 refined, input/performance/scaling_*.deck: press + 4 sliding steps) on 1 and on 2
processes with the same linear solver (MUMPS, distributed LU; GMRES + GAMG, PETSc's algebraic
multigrid), and on 1 process with the default serial solver for reference. Per run it reads the `cost:` line of `covcontact run --cost`: CPU and
peak memory per process, the time of element assembly, contact (search + points) and the linear
solve per process, and the bytes moved between processes per Newton iteration.

    /usr/bin/python3 scripts/bench_mpi.py [--sizes 57k,125k] [--build build]
        [--runs mumps_np1,mumps_np2,gamg_np1,gamg_np2,amg_np2,auto_np2] [--press-only] [--pin]
        [--twice] [--cores] [--predictor] [--output FILE.json]

The sizes bulk79k, bulk341k and bulk1.2M are the 3D bulk geometry of issue 13
(input/performance/bulk_79k.deck with its slab meshed 54 x 24 x 18, 90 x 40 x 30, 135 x 60 x 45),
whose target run is

    /usr/bin/python3 scripts/bench_mpi.py --sizes bulk1.2M --runs amg_np2 \
        --output docs/performance/bulk.json

--press-only runs the press step alone (for 1.2 M); --pin pins every run to cores (the two cores of
the development machine differ in speed by 1.45x); --twice runs two 1-process copies at once (is
memory bandwidth the limit?); --cores measures each core's speed first.

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
# The bulk geometry's sizes: the slab's elements along x, y, z in bulk_79k.deck's mesh line.
BULK_SLAB = {"bulk79k": (54, 24, 18), "bulk341k": (90, 40, 30), "bulk1.2M": (135, 60, 45)}


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
    # Fallbacks and switches of the linear solver (auto's GAMG -> BoomerAMG) go to stderr.
    notes = [line for line in result.stderr.splitlines() if "GMRES+" in line]
    if notes:
        record["solver_notes"] = notes[:20]
    return record


def run_twice_at_once(command, timeout):
    """Two copies of a 1-process run started together, each with its own results file: what one
    process gets of the machine when another busy process shares it (memory bandwidth, caches),
    without any communication between them. The ratio of a copy's wall time to the lone run's
    bounds the speed-up any 2-process run can reach here: 2 / ratio."""
    copies = []
    for copy in (1, 2):
        command_copy = list(command)
        output = command_copy.index("-o") + 1
        command_copy[output] = command_copy[output].replace(".h5", f"_copy{copy}.h5")
        copies.append(command_copy)
    start = time.monotonic()
    load = os.getloadavg()[0]
    processes = [subprocess.Popen(c, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for c in copies]
    records = []
    for process, command_copy in zip(processes, copies):
        try:
            stdout, stderr = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            for p in processes:
                p.kill()
            return {"command": " ".join(command), "timed_out": timeout, "load_before": load}
        cost = [line for line in stdout.splitlines() if line.startswith("cost: ")]
        record = {"exit_code": process.returncode, "wall_s": time.monotonic() - start}
        if cost:
            record.update(json.loads(cost[-1][len("cost: "):]))
        else:
            record["stderr"] = stderr[-2000:]
        records.append(record)
    return {"command": " ".join(command) + "  (two copies at once)", "load_before": load,
            "copies": records}


def configurations(args, deck, work):
    covcontact = os.path.join(args.build, "src", "app", "covcontact")
    mpirun = [shutil.which("mpirun"), "--allow-run-as-root", "--oversubscribe"]
    if args.pin:
        mpirun += ["--bind-to", "core", "--map-by", "core"]
    for name, prefix, solver in (("serial_default", [], None),
                                 ("mumps_np1", [], "mumps"),
                                 ("mumps_np2", mpirun + ["-np", "2"], "mumps"),
                                 ("gamg_np1", [], "gamg"),
                                 ("gamg_np2", mpirun + ["-np", "2"], "gamg"),
                                 ("amg_np2", mpirun + ["-np", "2"], "amg"),
                                 ("auto_np2", mpirun + ["-np", "2"], "auto")):
        for pinned, pin in pinnings(args, name):
            results = os.path.join(work, f"{os.path.basename(deck)[:-5]}_{pinned}.h5")
            command = pin + prefix + [covcontact, "run", deck, "-o", results, "-q", "--cost",
                                      "--threads", "1"]
            if solver:
                command += ["--solver", solver]
            yield pinned, command


def core_speeds(args):
    """The same 1-process run (the 11 k scaling deck) pinned to each core in turn, twice: CPU
    seconds per core. Cores of a virtual machine need not be equally fast."""
    covcontact = os.path.join(args.build, "src", "app", "covcontact")
    deck = os.path.join(ROOT, "input", "performance", "scaling_11k.deck")
    speeds = {}
    for round_ in (1, 2):
        for core in range(os.cpu_count()):
            before = os.times()
            subprocess.run(["taskset", "-c", str(core), covcontact, "run", deck, "-o",
                            os.path.join(args.build, "bench_mpi", f"core{core}.h5"), "-q",
                            "--threads", "1"], capture_output=True, check=True)
            after = os.times()
            cpu = (after.children_user - before.children_user
                   + after.children_system - before.children_system)
            speeds.setdefault(f"core{core}", []).append(cpu)
            print(f"core {core}, round {round_}: {cpu:.2f} CPU s", file=sys.stderr, flush=True)
    return speeds


def pinnings(args, name):
    """--pin: a 1-process run once on each core (taskset), a 2-process run one process per core
    (mpirun --bind-to core). On this machine the two cores differ in speed (core 0 took 1.45x
    the CPU time of core 1 for the same run), so an unpinned 1-process run is as fast as the
    core it happened to get, and a 2-process run waits for the process on the slower core."""
    if not args.pin:
        yield name, []
    elif name.endswith("_np1"):
        for core in range(os.cpu_count()):
            yield f"{name}_core{core}", ["taskset", "-c", str(core)]
    elif name.endswith("_np2"):
        yield f"{name}_bound", []
    else:
        yield name, []


def deck_copy(deck, work, press_only=False, predictor=False, size=None):
    """A copy of the deck in the work directory with its mesh path made absolute: its sliding
    phase dropped (press_only), `newton predictor=extrapolate` added after `solve` (predictor),
    the bulk deck's slab meshed for `size` (BULK_SLAB)."""
    with open(deck) as stream:
        lines = stream.read().splitlines()
    steps = [i for i, line in enumerate(lines) if line.strip().startswith("steps ")]
    if len(steps) != 2:
        sys.exit(f"{deck}: expected a press and a sliding `steps` line, found {len(steps)}")
    if press_only:
        del lines[steps[1]]
    if predictor:
        solve = [i for i, line in enumerate(lines) if line.strip() == "solve"]
        if len(solve) != 1:
            sys.exit(f"{deck}: expected one bare `solve` line")
        lines.insert(solve[0] + 1, "  newton predictor=extrapolate")
    folder = os.path.dirname(os.path.abspath(deck))
    for i, line in enumerate(lines):
        if line.startswith("mesh \""):
            relative = line.split('"')[1]
            lines[i] = line.replace(relative, os.path.normpath(os.path.join(folder, relative)), 1)
            if size in BULK_SLAB:
                given = "nx=54 ny=24 nz=18"
                if given not in lines[i]:
                    sys.exit(f"{deck}: the mesh line no longer says {given}")
                lines[i] = lines[i].replace(given, "nx={} ny={} nz={}".format(*BULK_SLAB[size]))
    suffix = ("_press" if press_only else "") + ("_predictor" if predictor else "")
    name = size if size in BULK_SLAB else os.path.basename(deck)[:-5]
    copy = os.path.join(work, name + suffix + ".deck")
    with open(copy, "w") as stream:
        stream.write("\n".join(lines) + "\n")
    return copy


def speedups(one, two):
    """Ratios 1 process / 2 processes of the slowest process's time per part."""
    ratio = {}
    for part in ("elements_s", "contact_s", "pattern_s", "linear_solve_s"):
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
    parser.add_argument("--twice", action="store_true",
                        help="after each 1-process run, run two copies of it at once: the "
                             "ceiling of a 2-process speed-up on this machine (shared memory "
                             "bandwidth), measured without any communication")
    parser.add_argument("--pin", action="store_true",
                        help="pin the runs to cores: each 1-process run once per core, the "
                             "2-process run one process per core (see pinnings())")
    parser.add_argument("--cores", action="store_true",
                        help="first measure each core's speed (core_speeds()) and store it")
    parser.add_argument("--press-only", action="store_true",
                        help="run only the press step of each deck (a copy in the work directory): "
                             "for sizes where five steps on one process do not fit in a session")
    parser.add_argument("--predictor", action="store_true",
                        help="run the decks with `newton predictor=extrapolate` (issue 14; a copy "
                             "in the work directory)")
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
    cores = core_speeds(args) if args.cores else previous.get("core_cpu_s")
    for size in args.sizes.split(","):
        deck = os.path.join(ROOT, "input", "performance", f"scaling_{size}.deck")
        if size in BULK_SLAB:
            deck = os.path.join(ROOT, "input", "performance", "bulk_79k.deck")
        if args.press_only or args.predictor or size in BULK_SLAB:
            deck = deck_copy(deck, work, args.press_only, args.predictor, size)
        runs = {}
        for name, command in configurations(args, deck, work):
            if name.split("_core")[0].removesuffix("_bound") not in args.runs.split(","):
                continue
            print(f"{size} {name}: {' '.join(command)}", file=sys.stderr, flush=True)
            runs[name] = run(command, args.timeout)
            if name.endswith("_np1") and args.twice:
                print(f"{size} {name} twice at once", file=sys.stderr, flush=True)
                runs[name + "_twice"] = run_twice_at_once(command, args.timeout)
        for solver in ("mumps", "gamg", "amg"):
            if f"{solver}_np1" in runs and f"{solver}_np2" in runs:
                runs[f"speedup_{solver}_np1_over_np2"] = speedups(runs[f"{solver}_np1"],
                                                                  runs[f"{solver}_np2"])
            for core in range(os.cpu_count()):
                one, two = f"{solver}_np1_core{core}", f"{solver}_np2_bound"
                if one in runs and two in runs:
                    runs[f"speedup_{solver}_np1_core{core}_over_np2"] = speedups(runs[one],
                                                                                 runs[two])
        results[size] = runs
        with open(args.output, "w") as stream:
            json.dump({"sizes": results, "core_cpu_s": cores}, stream, indent=1)
    print("| size | equations | run | Newton its | wall s | CPU s per process | peak RSS MiB per "
          "process | elements s | contact s | linear solve s | bytes per iteration |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for size, runs in results.items():
        for name in runs:
            if name.startswith("speedup") or name.endswith("_twice"):
                continue
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
        for name in ("mumps_np1_twice", "gamg_np1_twice"):
            twice, alone = runs.get(name, {}), runs.get(name[:-len("_twice")], {})
            if "copies" in twice and "wall_s" in alone and all("cpu_s" in c for c in twice["copies"]):
                walls = [c["wall_s"] for c in twice["copies"]]
                cpus = ", ".join(f"{c['cpu_s'][0]:.1f}" for c in twice["copies"])
                slowest = max(walls) / alone["wall_s"]
                print(f"| {size} | | {name}: two copies at once | | "
                      f"{', '.join(f'{w:.1f}' for w in walls)} | "
                      f"{cpus} | | "
                      f"{max(c['elements_s'][0] for c in twice['copies']):.2f} | "
                      f"{max(c['contact_s'][0] for c in twice['copies']):.2f} | "
                      f"{max(c['linear_solve_s'][0] for c in twice['copies']):.2f} | "
                      f"slowest copy {slowest:.2f}x the lone run: 2-process ceiling "
                      f"{2 / slowest:.2f}x |")
        for solver, label in (("mumps", "MUMPS"), ("gamg", "GMRES + GAMG")):
            for against in [""] + [f" core{core}" for core in range(os.cpu_count())]:
                ratio = runs.get(f"speedup_{solver}_np1{against.replace(' ', '_')}_over_np2", {})
                if ratio:
                    print(f"| {size} | | speed-up 1{against} -> 2 processes ({label}) | | "
                          + " | ".join(f"{k} {v:.2f}x" for k, v in ratio.items())
                          + " | | | | | |")


if __name__ == "__main__":
    main()
