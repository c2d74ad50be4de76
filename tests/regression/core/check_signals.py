#!/usr/bin/python3
"""Signals during a real run of neohooke_bending_long.deck (60 steps):

--case sigkill: the run is killed with SIGKILL at a random moment after it reported k steps
  (three kills). Every step group in the file must read back with h5py (contiguous, finite, the
  prescribed tip displacement to rounding, complete convergence rows), at least the k reported steps
  must be there, there is no /summary, and the XDMF and CSV sidecars mention only steps that
  exist in the file.
--case sigterm / sigint: the run must stop after the current iteration with exit code 4, and the
  file must hold a /summary saying "interrupted" and every converged (reported) step.

Usage: check_signals.py --covcontact BIN --decks input/verification/core --scratch DIR --case C
"""
import os
import random
import signal
import subprocess
import time

import h5py
import numpy as np

from core_command import (COMMAND_TIMEOUT_S, check, parse_arguments, read_reactions_csv,
                          step_names, xdmf_references)

DECK = "neohooke_bending_long.deck"
PLANNED_STEPS = 60
EXIT_INTERRUPTED = 4  # `covcontact --help`


def tip_displacement(time_value):
    return -5.0 * time_value / 60  # prescribe tip uy "-5*t/60"


# muParser may evaluate "-5*t/60" in another order (it folds constants): a few roundings.
EXPRESSION_ROUNDING = 4 * np.finfo(float).eps


# (steps reported before the kill, seed of the extra delay); the delay is drawn from
# [0, MAX_KILL_DELAY_S], about one step of this deck, so the kill lands inside a later step.
KILLS = [(2, 1), (4, 2), (6, 3)]
MAX_KILL_DELAY_S = 0.3
STEPS_BEFORE_SIGNAL = 3


def start_run(args, results):
    deck = os.path.join(args.decks, DECK)
    return subprocess.Popen([args.covcontact, "run", deck, "-o", results], cwd=args.scratch,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_step(process, step):
    """Reads progress lines until `step k/n` with k = step; returns the highest step seen."""
    for line in process.stdout:
        words = line.split()
        if words[:1] == ["step"]:
            reported = int(words[1].split("/")[0])
            if reported >= step:
                return reported
    process.wait()
    check(False, f"the run ended (exit {process.returncode}) before step {step}: "
                 f"{process.stderr.read()}")


def reported_after(lines, reported):
    """The highest step among `reported` and the progress lines in `lines`."""
    for line in lines:
        words = line.split()
        if words[:1] == ["step"]:
            reported = max(reported, int(words[1].split("/")[0]))
    return reported


def check_steps(h5, reported):
    """Every step group reads back; returns the step names. `reported` steps must be there."""
    names = step_names(h5)
    check(len(names) >= reported, f"{len(names)} step groups, {reported} were reported")
    tip = h5["mesh/node_sets/tip/nodes"][...]
    history = h5["convergence"][...]
    for name in names:
        group = h5["steps"][name]
        step, time_value = int(group.attrs["step"]), group.attrs["time"]
        displacement = group["displacement"][...]
        check(displacement.shape == h5["mesh/coordinates"].shape and
              np.all(np.isfinite(displacement)), f"step {step}: displacement unreadable")
        prescribed = tip_displacement(time_value)
        check(np.all(np.abs(displacement[tip, 1] - prescribed) <=
                     EXPRESSION_ROUNDING * abs(prescribed)),
              f"step {step}: tip uy is not the prescribed {tip_displacement(time_value)}")
        check(np.all(np.isfinite(group["stress"][...])), f"step {step}: stress unreadable")
        rows = history[history["step"] == step]
        last_attempt = rows[rows["attempt"] == rows["attempt"].max()]
        check(last_attempt["iteration"].tolist() ==
              list(range(1, int(group.attrs["iterations"]) + 1)),
              f"step {step}: convergence rows {last_attempt['iteration'].tolist()}")
    return names


def check_sidecars(h5, results, names, complete):
    """XDMF and CSV mention only existing steps (all of them if `complete`)."""
    stem = results[:-len(".h5")]
    xdmf = xdmf_references(stem + ".xdmf")
    _, csv_rows = read_reactions_csv(stem + "_reactions.csv")
    for count, what in ((len(xdmf), "XDMF"), (len(csv_rows), "CSV")):
        check(count <= len(names) and (count == len(names) or not complete),
              f"{what} lists {count} steps, the file has {len(names)}")
    for index, (time_value, references) in enumerate(xdmf):
        check(time_value == h5["steps"][names[index]].attrs["time"],
              f"XDMF step {index + 1} time {time_value}")
        for reference in references:
            file_name, path = reference.split(":", 1)
            check(file_name == os.path.basename(results) and path in h5,
                  f"XDMF step {index + 1} refers to missing {reference}")
    for index, row in enumerate(csv_rows):
        check(row[1] == h5["steps"][names[index]].attrs["time"], f"CSV row {index + 1} time")


def kill_case(args):
    checked = 0
    for steps_before, seed in KILLS:
        results = os.path.join(args.scratch, f"killed_{steps_before}.h5")
        process = start_run(args, results)
        reported = wait_for_step(process, steps_before)
        time.sleep(random.Random(seed).uniform(0, MAX_KILL_DELAY_S))
        process.send_signal(signal.SIGKILL)
        reported = reported_after(process.stdout, reported)  # printed before the kill
        process.wait(timeout=COMMAND_TIMEOUT_S)
        check(process.returncode == -signal.SIGKILL, f"exit {process.returncode}, not SIGKILL")
        with h5py.File(results, "r") as h5:
            names = check_steps(h5, reported)
            check("summary" not in h5, "a killed run has a /summary")
            check_sidecars(h5, results, names, complete=False)
        checked += len(names)
        print(f"killed after step {reported}: {len(names)} steps read back")
    print(f"OK: {len(KILLS)} runs killed with SIGKILL mid-run; all {checked} steps in the files "
          "read back, XDMF and CSV mention only those")


def interrupt_case(args, signal_number):
    results = os.path.join(args.scratch, "interrupted.h5")
    process = start_run(args, results)
    wait_for_step(process, STEPS_BEFORE_SIGNAL)
    process.send_signal(signal_number)
    # Plain reads (not communicate(), which would bypass the lines already buffered); stderr
    # holds two lines, so it cannot block the writer while stdout is read to its end.
    reported = reported_after(process.stdout, STEPS_BEFORE_SIGNAL)
    stderr = process.stderr.read()
    process.wait(timeout=COMMAND_TIMEOUT_S)
    check(process.returncode == EXIT_INTERRUPTED,
          f"exit {process.returncode}, expected {EXIT_INTERRUPTED}\n{stderr}")
    check("interrupted" in stderr, f"stderr does not say interrupted: {stderr}")
    check(reported < PLANNED_STEPS, "the run finished before the signal arrived")
    with h5py.File(results, "r") as h5:
        names = check_steps(h5, reported)
        summary = h5["summary"].attrs
        check(summary["outcome"] == "interrupted", f"summary outcome {summary['outcome']!r}")
        check(summary["steps"] == len(names) == reported,
              f"summary steps {summary['steps']}, {len(names)} groups, {reported} reported")
        check_sidecars(h5, results, names, complete=True)
    print(f"OK: {signal.Signals(signal_number).name} after step {STEPS_BEFORE_SIGNAL}: exit 4, "
          f"/summary interrupted with all {reported} converged steps")


def main():
    args = parse_arguments(__doc__, lambda parser: parser.add_argument(
        "--case", required=True, choices=["sigkill", "sigterm", "sigint"]))
    if args.case == "sigkill":
        kill_case(args)
    else:
        interrupt_case(args, signal.SIGTERM if args.case == "sigterm" else signal.SIGINT)


if __name__ == "__main__":
    main()
