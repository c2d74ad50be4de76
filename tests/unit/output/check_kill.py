#!/usr/bin/python3
"""SIGKILL test of the per-step flush. kill_writer (paced) writes k steps, then "solves" step k+1
(appends its Newton iteration rows, waits for us); we kill it with SIGKILL at a random moment of
that solve and check with h5py that every reported step reads back with the right values, that
the convergence rows of those steps are complete, and that the XDMF and CSV sidecars cover them.

--measure N instead kills a back-to-back (continuous) writer N times at random moments, so that
kills also land inside writeStep and H5Fflush, and reports how many files were damaged
(a measurement for docs/output-format.md, not a pass/fail test).

Usage: check_kill.py KILL_WRITER WORK_DIR [--kills N] [--measure N]
"""
import argparse
import os
import random
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ElementTree

import numpy as np

NUM_NODES = 63  # the synthetic mesh of synthetic_run.cpp
KILLS = 20
MAX_STEPS_BEFORE_KILL = 8
MAX_KILL_DELAY_S = 0.025  # step k+1's iterations take 5-20 ms, then the writer waits for us
MEASURE_MAX_DELAY_S = 0.15


def iterations_of(step):
    return step % 4 + 1


def sidecars(path):
    return path[:-3] + ".xdmf", path[:-3] + "_reactions.csv"


def remove_outputs(path):
    for stale in (path,) + sidecars(path):
        if os.path.exists(stale):
            os.remove(stale)


def finish_kill(process):
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    if process.returncode != -signal.SIGKILL:
        sys.exit(f"FAIL kill_writer ended with {process.returncode}, not by SIGKILL")


def kill_while_solving(writer, path, steps, delay):
    """Lets the writer write `steps` steps, kills it while it solves the next; returns `steps`."""
    remove_outputs(path)
    process = subprocess.Popen([writer, path, "100000", "paced"], stdin=subprocess.PIPE,
                               stdout=subprocess.PIPE, text=True)
    for step in range(1, steps + 1):
        process.stdin.write("\n")
        process.stdin.flush()
        line = process.stdout.readline()
        if line != f"step {step}\n":
            process.kill()
            sys.exit(f"FAIL kill_writer printed {line!r}, expected step {step}")
    time.sleep(delay)
    finish_kill(process)
    return steps


def kill_while_writing(writer, path, delay):
    """Kills a back-to-back writer after `delay`; returns the last step it reported."""
    remove_outputs(path)
    process = subprocess.Popen([writer, path, "100000", "continuous"], stdout=subprocess.PIPE,
                               text=True)
    reported = int(process.stdout.readline().split()[1])
    time.sleep(delay)
    os.kill(process.pid, signal.SIGKILL)
    for line in process.stdout:  # steps finished before the kill
        reported = int(line.split()[1])
    process.wait()
    return reported


def check_file(path, reported):
    import h5py  # imported here: --measure runs this in a child process (damaged files may crash it)
    with h5py.File(path, "r") as h5:
        for step in range(1, reported + 1):
            group = h5["steps/%06d" % step]
            expected_displacement = (1000.0 * step + 3.0 * np.arange(NUM_NODES)[:, None]
                                     + np.arange(3)[None, :])
            checks = [
                ("time", group.attrs["time"], 0.5 * step),
                ("iterations", group.attrs["iterations"], iterations_of(step)),
                ("displacement", group["displacement"][...], expected_displacement),
                ("set_reactions", group["set_reactions"][...], [[step, -step, 0.5]]),
                ("pair1 total_force", group["contact/pair1/total_force"][...],
                 [step, 2.0 * step, 3.0 * step]),
            ]
            for name, stored, expected in checks:
                if not np.array_equal(np.asarray(stored), np.asarray(expected)):
                    sys.exit(f"FAIL {path} step {step} {name}: {stored} != {expected}")
        rows = int(np.count_nonzero(h5["convergence"]["step"] <= reported))
        wanted = sum(iterations_of(step) for step in range(1, reported + 1))
        if rows != wanted:
            sys.exit(f"FAIL {path}: {rows} convergence rows of steps <= {reported}, not {wanted}")
    xdmf, csv = sidecars(path)
    xdmf_steps = len(ElementTree.parse(xdmf).getroot().findall("Domain/Grid/Grid"))
    with open(csv) as stream:
        csv_rows = sum(1 for line in stream if line.endswith("\n")) - 1
    if xdmf_steps < reported or csv_rows < reported:
        sys.exit(f"FAIL {path}: XDMF lists {xdmf_steps}, CSV {csv_rows} steps; {reported} reported")


def measure(writer, path, runs):
    generator = random.Random(2024)
    damaged, steps = 0, 0
    for run in range(runs):
        reported = kill_while_writing(writer, path, generator.uniform(0, MEASURE_MAX_DELAY_S))
        steps += reported
        check = subprocess.run([sys.executable, __file__, "--check", path, str(reported)],
                               capture_output=True, text=True)
        if check.returncode != 0:
            damaged += 1
            print(f"run {run}: {(check.stderr or check.stdout).strip().splitlines()[-1:]}")
    print(f"continuous writing: {runs} kills, {steps} reported steps, {damaged} damaged files")


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--check":
        check_file(sys.argv[2], int(sys.argv[3]))
        return
    parser = argparse.ArgumentParser()
    parser.add_argument("writer")
    parser.add_argument("workdir")
    parser.add_argument("--kills", type=int, default=KILLS)
    parser.add_argument("--measure", type=int, default=0)
    args = parser.parse_args()
    os.makedirs(args.workdir, exist_ok=True)
    path = os.path.join(args.workdir, "killed.h5")
    if args.measure:
        measure(args.writer, path, args.measure)
        return
    generator = random.Random(12345)
    total = 0
    for _ in range(args.kills):
        steps = generator.randint(1, MAX_STEPS_BEFORE_KILL)
        total += kill_while_solving(args.writer, path, steps,
                                    generator.uniform(0, MAX_KILL_DELAY_S))
        check_file(path, steps)
    print(f"OK: {args.kills} runs killed with SIGKILL while solving, {total} reported steps all "
          "read back exactly (values, convergence rows, XDMF, CSV)")


if __name__ == "__main__":
    main()
