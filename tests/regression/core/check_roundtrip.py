#!/usr/bin/python3
"""HDF5 round trip through the real command: `covcontact run neohooke_bending.deck -o run.h5`,
then the printed step lines and the reactions CSV must agree exactly with what h5py reads from
run.h5 (times, iteration counts, summed set reactions), the set reactions must be the sums of the
stored nodal reactions, the stored displacements must equal the prescribed values, and the file
must hold the deck text (with its include) and the command line.

Usage: check_roundtrip.py --covcontact BIN --decks input/verification/core --scratch DIR
"""
import math
import os

import h5py
import numpy as np

from core_command import (check, parse_arguments, read_reactions_csv, run, step_lines,
                          step_names, xdmf_references)

DECK = "neohooke_bending.deck"
INCLUDED = "neohooke_bending_model.inc"
STEPS = 4
TIP_DISPLACEMENT_RATE = -5.0  # prescribe tip uy "-5*t"
# Components each set constrains completely (fix clamp all; prescribe tip uy): there the summed
# set reaction is a plain sum of the stored nodal reactions.
CONSTRAINED_COMPONENTS = {"clamp": (0, 1, 2), "tip": (1,)}
COMPONENTS = "xyz"
EPSILON = np.finfo(float).eps


def summation_tolerance(values):
    """Bound of the difference of two summation orders of `values`: n eps sum |v|."""
    return len(values) * EPSILON * math.fsum(abs(value) for value in values)


def check_step(h5, name, csv_row, header, printed):
    group = h5["steps"][name]
    step = int(group.attrs["step"])
    check(step == int(csv_row[0]) and group.attrs["time"] == csv_row[1],
          f"step {name}: h5 step/time {step}/{group.attrs['time']} != CSV {csv_row[:2]}")
    check(group.attrs["iterations"] == csv_row[2] == printed[step],
          f"step {step}: iterations h5 {group.attrs['iterations']}, CSV {csv_row[2]}, "
          f"printed {printed.get(step)}")
    set_reactions = group["set_reactions"][...]
    names = [str(n) for n in group["set_reactions"].attrs["names"]]
    check(sorted(names) == sorted(CONSTRAINED_COMPONENTS), f"set_reactions names {names}")
    reaction = group["reaction"][...]
    displacement = group["displacement"][...]
    for row, set_name in enumerate(names):
        for component, axis in enumerate(COMPONENTS):
            column = header.index(f"{set_name}_F{axis}")
            check(set_reactions[row, component] == csv_row[column],
                  f"step {step} {set_name}.{axis}: h5 {set_reactions[row, component]!r} "
                  f"!= CSV {csv_row[column]!r}")
        nodes = h5["mesh/node_sets"][set_name]["nodes"][...]
        for component in CONSTRAINED_COMPONENTS[set_name]:
            nodal = reaction[nodes, component].tolist()
            difference = abs(set_reactions[row, component] - math.fsum(nodal))
            check(difference <= summation_tolerance(nodal),
                  f"step {step} {set_name}.{COMPONENTS[component]}: set reaction differs from "
                  f"the sum of nodal reactions by {difference:.3g}")
    time = group.attrs["time"]
    tip = h5["mesh/node_sets/tip/nodes"][...]
    clamp = h5["mesh/node_sets/clamp/nodes"][...]
    check(np.all(displacement[tip, 1] == TIP_DISPLACEMENT_RATE * time),
          f"step {step}: tip uy is not the prescribed {TIP_DISPLACEMENT_RATE * time}")
    check(np.all(displacement[clamp] == 0), f"step {step}: clamped nodes moved")
    check(np.all(np.isfinite(displacement)), f"step {step}: non-finite displacement")
    rows = h5["convergence"][...]
    rows = rows[rows["step"] == step]
    check(rows["iteration"].tolist() == list(range(1, int(group.attrs["iterations"]) + 1)),
          f"step {step}: convergence rows {rows['iteration'].tolist()}")
    return int(group.attrs["iterations"])


def check_attributes(h5, deck, command):
    check(h5.attrs["command_line"] == " ".join(command),
          f"command_line attribute {h5.attrs['command_line']!r}")
    deck_text = h5.attrs["deck_text"]
    with open(deck) as stream:
        main_text = stream.read()
    with open(os.path.join(os.path.dirname(deck), INCLUDED)) as stream:
        included_text = stream.read()
    check(deck_text.startswith(main_text), "deck_text does not start with the deck file")
    check(included_text in deck_text and "# ---- included file:" in deck_text,
          "deck_text lacks the included file")
    check(h5.attrs["title"] == "Neo-Hooke cantilever bent by a tip displacement of L/2",
          f"title attribute {h5.attrs['title']!r}")


def main():
    args = parse_arguments(__doc__)
    deck = os.path.join(args.decks, DECK)
    command = [args.covcontact, "run", deck, "-o", "run.h5"]
    result = run(command, args.scratch)
    check(result.returncode == 0, f"exit {result.returncode}\n{result.stdout}{result.stderr}")
    printed = step_lines(result.stdout)
    check(sorted(printed) == list(range(1, STEPS + 1)), f"printed steps {sorted(printed)}")
    header, csv_rows = read_reactions_csv(os.path.join(args.scratch, "run_reactions.csv"))
    check(len(csv_rows) == STEPS, f"{len(csv_rows)} CSV rows")
    with h5py.File(os.path.join(args.scratch, "run.h5"), "r") as h5:
        names = step_names(h5)
        check(len(names) == STEPS, f"{len(names)} step groups")
        iterations = sum(check_step(h5, name, row, header, printed)
                         for name, row in zip(names, csv_rows))
        check_attributes(h5, deck, command)
        summary = h5["summary"].attrs
        check(summary["outcome"] == "completed" and summary["steps"] == STEPS
              and summary["total_iterations"] == iterations,
              f"summary {dict(summary)}")
        times = [h5["steps"][name].attrs["time"] for name in names]
    xdmf = xdmf_references(os.path.join(args.scratch, "run.xdmf"))
    check([time for time, _ in xdmf] == times, f"XDMF times {[t for t, _ in xdmf]} != {times}")
    print(f"OK: {STEPS} steps of {DECK}: printed iterations, CSV and h5py agree exactly "
          f"({iterations} Newton iterations); set reactions = sums of nodal reactions; "
          "prescribed displacements exact; deck text and command line stored")


if __name__ == "__main__":
    main()
