#!/usr/bin/python3
"""No lost results (issue 7): signals during a frictional contact run and `--restart`.

Decks from input/stress: restart_6_1.deck (example 6.1 with friction, 41 steps) and
cutback_equivalence.deck (a step that is cut back to 1/16 and regrows).

--case sigkill: the run is killed with SIGKILL after it reported k steps (k = 3, 8, 15). Every
  step group in the file reads back with h5py, with finite displacements and complete restart
  data (element and contact history for every point); there is no /summary.
--case sigterm / sigint: the run stops after the current iteration with exit code 4; the file has
  a /summary saying "interrupted" with every converged (reported) step, and a step that was
  being iterated is not among them.
--case restart_after_sigterm / restart_after_sigkill: the interrupted (killed) run is continued
  with `--restart FILE` from its last stored step; every step after it has the uninterrupted
  run's iteration count, and its forces (set reactions, contact force) and displacements agree
  to 1e-10.
--case restart_from_step: the same with `--from-step 12` of a complete run.
--case restart_after_cutbacks: cutback_equivalence.deck continued from step 3, inside the regrowth
  after its cut-backs: the same step times (the stored step size) and iteration counts.
--case restart_errors: a restart that cannot work stops with the documented exit code and says
  why (the restart file as output: 1; --from-step without --restart: 1; a missing step: 6; not a
  results file: 6; a deck with another mesh: 2).

Usage: check_no_lost_results.py --covcontact BIN --decks input/stress --scratch DIR --case C
"""
import argparse
import os
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from script_checks import check  # noqa: E402  (tests/support)

RESTART_DECK = "restart_6_1.deck"
CUTBACK_DECK = "cutback_equivalence.deck"
PLANNED_STEPS = 41
HISTORY_ROWS = 29  # ContactPair::kHistoryRows
# Longest time one command may take on a loaded 2-core machine.
COMMAND_TIMEOUT_S = 120
# The continued run repeats the same arithmetic; 1e-10 leaves room for nothing but round-off.
RESTART_TOLERANCE = 1e-10
EXIT = {"ok": 0, "usage": 1, "input": 2, "interrupted": 4, "io": 6}  # `covcontact --help`


def command(args, deck, results, *extra):
    return [args.covcontact, "run", os.path.join(args.decks, deck), "-o", results,
            "--threads", "1", *extra]


def run(args, deck, results, *extra):
    """Runs `covcontact run` to completion; returns the CompletedProcess."""
    return subprocess.run(command(args, deck, results, *extra), cwd=args.scratch,
                          capture_output=True, text=True, timeout=COMMAND_TIMEOUT_S)


def run_ok(args, deck, results, *extra):
    result = run(args, deck, results, *extra)
    check(result.returncode == EXIT["ok"],
          f"{' '.join(result.args)}: exit {result.returncode}\n{result.stderr}")
    return result


def reported_steps(lines):
    """The highest k of the plain progress lines `step k/n ...`."""
    reported = 0
    for line in lines:
        words = line.split()
        if words[:1] == ["step"]:
            reported = max(reported, int(words[1].split("/")[0]))
    return reported


def interrupt(args, results, after_step, signal_number):
    """Starts a run, sends the signal once step `after_step` is reported; returns the process
    state: (exit code, highest reported step, stderr)."""
    process = subprocess.Popen(command(args, RESTART_DECK, results), cwd=args.scratch,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    reported = 0
    for line in process.stdout:
        reported = max(reported, reported_steps([line]))
        if reported >= after_step:
            process.send_signal(signal_number)
            break
    reported = max(reported, reported_steps(process.stdout.readlines()))
    stderr = process.stderr.read()
    process.wait(timeout=COMMAND_TIMEOUT_S)
    check(reported < PLANNED_STEPS, "the run finished before the signal arrived")
    return process.returncode, reported, stderr


def step_names(h5):
    return sorted(h5["steps"].keys())


def check_readable(h5, reported):
    """Every step group reads back with complete restart data; returns the step numbers."""
    names = step_names(h5)
    steps = [int(h5["steps"][name].attrs["step"]) for name in names]
    check(steps == list(range(1, len(steps) + 1)), f"step groups {steps} are not 1..n")
    check(len(steps) >= reported, f"{len(steps)} step groups, {reported} were reported")
    coordinates = h5["mesh/coordinates"].shape
    for name in names:
        group = h5["steps"][name]
        displacement = group["displacement"][...]
        check(displacement.shape == coordinates and np.all(np.isfinite(displacement)),
              f"step {name}: displacement unreadable")
        restart = group["restart"]
        points = group["contact/interface/gap"].shape[0]
        history = restart["contact_history/interface"][...]
        check(history.shape == (points, HISTORY_ROWS) and np.all(np.isfinite(history)),
              f"step {name}: contact history {history.shape}, expected ({points}, {HISTORY_ROWS})")
        check(set(restart["element_history"].keys()) == {"block", "base"},
              f"step {name}: element history of {list(restart['element_history'].keys())}")
        check(0 < restart.attrs["step_fraction"] <= 1, f"step {name}: step fraction")
    return steps


def compare_continued(reference_path, continued_path, first_step):
    """Steps >= first_step of the continued run against the uninterrupted one."""
    with h5py.File(reference_path, "r") as reference, h5py.File(continued_path, "r") as continued:
        names = step_names(continued)
        check(names and int(continued["steps"][names[0]].attrs["step"]) == first_step,
              f"the continued run starts at {names[:1]}, expected step {first_step}")
        check(names == [name for name in step_names(reference)
                        if int(reference["steps"][name].attrs["step"]) >= first_step],
              "the continued run does not write the uninterrupted run's remaining steps")
        worst = 0.0
        for name in names:
            a, b = reference["steps"][name], continued["steps"][name]
            for attribute in ("time", "iterations", "cutbacks"):
                check(a.attrs[attribute] == b.attrs[attribute],
                      f"step {name}: {attribute} {b.attrs[attribute]}, uninterrupted "
                      f"{a.attrs[attribute]}")
            for field in ("set_reactions", "contact/interface/total_force", "displacement"):
                expected, actual = a[field][...], b[field][...]
                scale = np.abs(expected).max()
                error = np.abs(actual - expected).max() / scale
                worst = max(worst, error)
                check(error <= RESTART_TOLERANCE, f"step {name}: {field} differs by {error:.2e}")
        check(continued["summary"].attrs["outcome"] == "completed", "continued run not completed")
    return len(names), worst


def kill_case(args, then_restart):
    reference = os.path.join(args.scratch, "uninterrupted.h5")
    if then_restart:
        run_ok(args, RESTART_DECK, reference)
    for after_step in (3, 8, 15):
        results = os.path.join(args.scratch, f"killed_{after_step}.h5")
        code, reported, _ = interrupt(args, results, after_step, signal.SIGKILL)
        check(code == -signal.SIGKILL, f"exit {code}, not SIGKILL")
        with h5py.File(results, "r") as h5:
            steps = check_readable(h5, reported)
            check("summary" not in h5, "a killed run has a /summary")
        print(f"killed after step {reported}: all {len(steps)} stored steps read back")
        if then_restart:
            continued = os.path.join(args.scratch, f"continued_{after_step}.h5")
            run_ok(args, RESTART_DECK, continued, "--restart", results)
            count, worst = compare_continued(reference, continued, steps[-1] + 1)
            print(f"  continued from step {steps[-1]}: {count} steps as uninterrupted "
                  f"(largest difference {worst:.1e})")


def interrupt_case(args, signal_number, then_restart):
    results = os.path.join(args.scratch, "interrupted.h5")
    code, reported, stderr = interrupt(args, results, 5, signal_number)
    check(code == EXIT["interrupted"], f"exit {code}, expected 4\n{stderr}")
    check("interrupted" in stderr, f"stderr does not say interrupted: {stderr}")
    with h5py.File(results, "r") as h5:
        steps = check_readable(h5, reported)
        summary = h5["summary"].attrs
        check(summary["outcome"] == "interrupted", f"summary outcome {summary['outcome']!r}")
        check(summary["steps"] == len(steps) == reported,
              f"summary steps {summary['steps']}, {len(steps)} groups, {reported} reported")
        # A step being iterated when the signal came is discarded: its rows, if any, are the
        # only ones beyond the last stored step.
        rows = h5["convergence"][...]
        check(np.all(rows["step"] <= steps[-1] + 1), "convergence rows beyond the next step")
    name = signal.Signals(signal_number).name
    print(f"{name} after step 5: exit 4, /summary interrupted with all {reported} steps")
    if then_restart:
        reference = os.path.join(args.scratch, "uninterrupted.h5")
        run_ok(args, RESTART_DECK, reference)
        continued = os.path.join(args.scratch, "continued.h5")
        result = run_ok(args, RESTART_DECK, continued, "--restart", results)
        check(f"continuing from step {steps[-1]}" in result.stdout, result.stdout)
        count, worst = compare_continued(reference, continued, steps[-1] + 1)
        print(f"continued from step {steps[-1]}: {count} steps with the uninterrupted run's "
              f"iterations, forces and displacements (largest difference {worst:.1e})")


def from_step_case(args):
    reference = os.path.join(args.scratch, "uninterrupted.h5")
    run_ok(args, RESTART_DECK, reference)
    continued = os.path.join(args.scratch, "continued.h5")
    run_ok(args, RESTART_DECK, continued, "--restart", reference, "--from-step", "12")
    count, worst = compare_continued(reference, continued, 13)
    print(f"--from-step 12: {count} steps as uninterrupted (largest difference {worst:.1e})")


def cutback_case(args):
    reference = os.path.join(args.scratch, "uninterrupted.h5")
    run_ok(args, CUTBACK_DECK, reference)
    with h5py.File(reference, "r") as h5:
        fractions = [h5["steps"][name]["restart"].attrs["step_fraction"] for name in step_names(h5)]
    check(fractions[2] < 1, f"step 3 is not inside the regrowth: fractions {fractions}")
    continued = os.path.join(args.scratch, "continued.h5")
    run_ok(args, CUTBACK_DECK, continued, "--restart", reference, "--from-step", "3")
    count, worst = compare_continued(reference, continued, 4)
    print(f"continued inside the regrowth (step size {fractions[2]} dt): {count} steps at the "
          f"same times with the same iterations (largest difference {worst:.1e})")


def errors_case(args):
    reference = os.path.join(args.scratch, "uninterrupted.h5")
    run_ok(args, CUTBACK_DECK, reference)
    cases = [
        ("the restart file as output", CUTBACK_DECK, reference, ["--restart", reference],
         EXIT["usage"], "is the restart file"),
        ("--from-step without --restart", CUTBACK_DECK, "a.h5", ["--from-step", "2"],
         EXIT["usage"], "--restart"),
        ("a step that was not stored", CUTBACK_DECK, "b.h5",
         ["--restart", reference, "--from-step", "99"], EXIT["io"],
         "has no restart data for step 99"),
        ("not a results file", CUTBACK_DECK, "c.h5",
         ["--restart", os.path.join(args.decks, CUTBACK_DECK)], EXIT["io"], "cutback_equivalence"),
        ("a deck with another mesh", "slave_on_master_vertices.deck", "d.h5",
         ["--restart", reference], EXIT["input"], "does not fit the deck's model"),
    ]
    for what, deck, results, extra, expected, fragment in cases:
        result = run(args, deck, os.path.join(args.scratch, results), *extra)
        check(result.returncode == expected,
              f"{what}: exit {result.returncode}, expected {expected}\n{result.stderr}")
        check(fragment in result.stderr, f"{what}: stderr lacks {fragment!r}:\n{result.stderr}")
        print(f"{what}: exit {expected}, {result.stderr.strip().splitlines()[-1]}")
    with h5py.File(reference, "r") as h5:
        check("summary" in h5 and len(h5["steps"]) == 9, "the restart file was modified")


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--decks", required=True, help="input/stress")
    parser.add_argument("--scratch", required=True, help="working directory (emptied first)")
    parser.add_argument("--case", required=True,
                        choices=["sigkill", "sigterm", "sigint", "restart_after_sigterm",
                                 "restart_after_sigkill", "restart_from_step",
                                 "restart_after_cutbacks", "restart_errors"])
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    started = time.monotonic()
    if args.case in ("sigkill", "restart_after_sigkill"):
        kill_case(args, then_restart=args.case == "restart_after_sigkill")
    elif args.case in ("sigterm", "sigint", "restart_after_sigterm"):
        number = signal.SIGINT if args.case == "sigint" else signal.SIGTERM
        interrupt_case(args, number, then_restart=args.case == "restart_after_sigterm")
    elif args.case == "restart_from_step":
        from_step_case(args)
    elif args.case == "restart_after_cutbacks":
        cutback_case(args)
    else:
        errors_case(args)
    print(f"OK ({time.monotonic() - started:.1f} s)")


if __name__ == "__main__":
    main()
