"""Runs of the performance benchmark (issue 8): each program run is watched for the time and
memory limits, and its wall time, CPU time and peak RSS are taken from the kernel (wait4), so
that runs on a shared, loaded machine can be judged by CPU time as well. Used by bench.py."""

import csv
import json
import os
import re
import shutil
import signal
import subprocess
import time

import bench_calculix
import ironing_predictor

POLL_SECONDS = 0.25


def load_average():
    with open("/proc/loadavg") as stream:
        return float(stream.read().split()[0])


def resident_bytes(pid):
    """VmRSS of a live process, 0 if it is gone."""
    try:
        with open(f"/proc/{pid}/status") as stream:
            for line in stream:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def cpu_seconds(pid):
    """User + system CPU time of a live process (all threads), 0 if it is gone."""
    try:
        with open(f"/proc/{pid}/stat") as stream:
            fields = stream.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return 0.0


def measure(command, cwd, env, limit_seconds, limit_bytes):
    """Runs `command`, killing it at the limits. Returns wall/CPU seconds, peak RSS, stdout,
    exit code and `stopped` ("time", "memory" or None). The time limit applies to the run's
    CPU time per thread, or to its wall time when the machine is idle enough for the two to
    agree: on a shared, loaded machine the wall time of a run is mostly waiting for a core."""
    threads = int(env.get("OMP_NUM_THREADS", "1"))
    os.makedirs(cwd, exist_ok=True)
    stdout_path = os.path.join(cwd, "stdout.txt")
    load_before = load_average()
    with open(stdout_path, "w") as stdout, open(os.path.join(cwd, "stderr.txt"), "w") as stderr:
        start = time.monotonic()
        process = subprocess.Popen(command, cwd=cwd, env=env, stdout=stdout, stderr=stderr)
        stopped = None
        while True:
            pid, status, usage = os.wait4(process.pid, os.WNOHANG)
            if pid:
                break
            elapsed = min(time.monotonic() - start, cpu_seconds(process.pid) / threads)
            if stopped is None and elapsed > limit_seconds:
                stopped = "time"
            elif stopped is None and resident_bytes(process.pid) > limit_bytes:
                stopped = "memory"
            if stopped:
                process.send_signal(signal.SIGKILL)
            time.sleep(POLL_SECONDS)
        wall = time.monotonic() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    with open(stdout_path) as stream:
        output = stream.read()
    return {"command": " ".join(command), "wall": wall, "cpu": usage.ru_utime + usage.ru_stime,
            "peak_rss_bytes": usage.ru_maxrss * 1024, "exit_code": process.returncode,
            "stopped": stopped, "load_before": load_before, "load_after": load_average(),
            "stdout": output}


def json_lines(text):
    return [json.loads(line) for line in text.splitlines() if line.startswith("{")]


class Runner:
    def __init__(self, build, work, limit_seconds, limit_bytes):
        build = os.path.abspath(build)
        self.driver = os.path.join(build, "tests", "regression", "performance", "covcontact_bench")
        self.covcontact = os.path.join(build, "src", "app", "covcontact")
        for program in (self.driver, self.covcontact):
            if not os.access(program, os.X_OK):
                raise SystemExit(f"bench: {program} missing: build first (see README.md)")
        self.work = work
        self.limit_seconds = limit_seconds
        self.limit_bytes = limit_bytes

    def environment(self, threads):
        env = dict(os.environ)
        env["OMP_NUM_THREADS"] = str(threads)
        # Idle OpenMP threads sleep instead of spinning: the machine is shared (see assembler.cpp).
        env.setdefault("OMP_WAIT_POLICY", "PASSIVE")
        return env

    def run_driver(self, name, deck, threads, extra, library_path=None, limit_seconds=None):
        cwd = os.path.join(self.work, f"{name}_t{threads}_{extra[0].strip('-') if extra else 'run'}")
        command = [self.driver, deck, "--threads", str(threads)] + (extra or ["-o", "run.h5"])
        print(f"bench: {' '.join(command)}", flush=True)
        env = self.environment(threads)
        if library_path:
            env["LD_LIBRARY_PATH"] = library_path
        result = measure(command, cwd, env, limit_seconds or self.limit_seconds,
                         self.limit_bytes)
        result["records"] = json_lines(result.pop("stdout"))
        shutil.rmtree(cwd, ignore_errors=True)
        return result

    def scaling(self, sizes, threads):
        """Every size with every thread count, up to the first run stopped by a limit."""
        runs, stopped = [], None
        for name, deck in sizes:
            for count in threads:
                result = self.run_driver(name, deck, count, None)
                result["size"] = name
                runs.append(result)
                if result["stopped"] or result["exit_code"] != 0:
                    stopped = {"size": name, "threads": count, "by": result["stopped"] or
                               f"exit code {result['exit_code']}"}
            if stopped:
                break
        return {"runs": runs, "stopped": stopped}

    def memory(self, name, deck):
        """One run with the direct solvers (CHOLMOD, UMFPACK once friction slips), whose largest
        factor the memory target compares the peak RSS with. It takes ~10 min at 232 k on an
        idle machine, so it gets twice the scaling runs' time limit."""
        result = self.run_driver(name, deck, 1, ["--solver", "cholmod", "-o", "run.h5"],
                                 limit_seconds=2 * self.limit_seconds)
        result["size"] = name
        return result

    def series(self, sizes, mode):
        """The driver in `mode` ("--orderings" or "--search") on each size, one thread, up to
        the first run stopped by a limit."""
        runs = []
        for name, deck in sizes:
            result = self.run_driver(name, deck, 1, [mode])
            result["size"] = name
            runs.append(result)
            if result["stopped"] or result["exit_code"] != 0:
                break
        return runs

    def blas(self, sizes, variants):
        """The orderings comparison (factorizations) under each BLAS: `variants` maps a name to
        the directory whose libblas.so.3 / liblapack.so.3 the loader should take."""
        runs = []
        for name, deck in sizes:
            for blas, library_path in variants.items():
                result = self.run_driver(name, deck, 1, ["--orderings"], library_path)
                result["size"], result["blas"] = name, blas
                runs.append(result)
        return runs

    def calculix(self, cases, loading, threads=1):
        """CalculiX and `covcontact run` on the same deck pair, one after the other."""
        comparisons = []
        for name, deck, inp in cases:
            cwd = os.path.join(self.work, f"calculix_{name}")
            shutil.rmtree(cwd, ignore_errors=True)
            os.makedirs(cwd)
            shutil.copy(inp, os.path.join(cwd, "job.inp"))
            env = self.environment(threads)
            env["CCX_NPROC_EQUATION_SOLVER"] = str(threads)
            print(f"bench: ccx {inp}", flush=True)
            ccx = measure(["ccx", "-i", "job"], cwd, env, self.limit_seconds, self.limit_bytes)
            ccx.pop("stdout")
            ccx.update(bench_calculix.read_sta(os.path.join(cwd, "job.sta")))
            ccx["curve"] = bench_calculix.read_reaction_totals(os.path.join(cwd, "job.dat"))
            print(f"bench: covcontact run {deck}", flush=True)
            ours = measure([self.covcontact, "run", deck, "-o", "run.h5", "--threads",
                            str(threads)], cwd, env, self.limit_seconds, self.limit_bytes)
            ours["summary"] = ours.pop("stdout").strip().splitlines()[-1:]
            ours["curve"], ours["iterations"] = read_reactions_csv(
                os.path.join(cwd, "run_reactions.csv"), "block_top")
            # The same deck with the extrapolating predictor (CalculiX starts each increment
            # from the last one's velocity): a user's choice for a steady slide, at the same
            # convergence criterion.
            variant = extrapolating_deck(deck, os.path.join(cwd, "extrapolate.deck"))
            print(f"bench: covcontact run {deck} with predictor=extrapolate", flush=True)
            extrapolating = measure([self.covcontact, "run", variant, "-o", "extrapolate.h5",
                                     "--threads", str(threads)], cwd, env, self.limit_seconds,
                                    self.limit_bytes)
            extrapolating["summary"] = extrapolating.pop("stdout").strip().splitlines()[-1:]
            extrapolating["curve"], extrapolating["iterations"] = read_reactions_csv(
                os.path.join(cwd, "extrapolate_reactions.csv"), "block_top")
            comparisons.append({"mesh": name, "threads": threads, "calculix": ccx,
                                "covcontact": ours, "covcontact_extrapolate": extrapolating})
            shutil.rmtree(cwd, ignore_errors=True)
        return comparisons


def extrapolating_deck(deck, path):
    """Writes `deck` with `newton predictor=extrapolate` in its solve block
    (ironing_predictor.with_predictor, as the issue 14 tables run it) to `path`, the mesh path
    made absolute, and returns `path`."""
    base = os.path.dirname(os.path.abspath(deck))
    with open(deck) as stream:
        text = re.sub(r'^(\s*mesh\s+)"([^"/][^"]*)"',
                      lambda m: f'{m.group(1)}"{os.path.join(base, m.group(2))}"', stream.read(),
                      flags=re.M)
    with open(path, "w") as out:
        out.write(ironing_predictor.with_predictor(text))
    return path


def read_reactions_csv(path, node_set):
    """[(time, Fx, Fy, Fz)] of a node set's summed reaction, and the total iterations."""
    curve, iterations = [], 0
    with open(path) as stream:
        for row in csv.DictReader(stream):
            curve.append((float(row["time"]), float(row[f"{node_set}_Fx"]),
                          float(row[f"{node_set}_Fy"]), float(row[f"{node_set}_Fz"])))
            iterations += int(row["iterations"])
    return curve, iterations
