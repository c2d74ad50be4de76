"""`solve solver=...` on a paper deck (issue 13): the Newton iteration counts per step of every
linear solver against the stored reference of the direct pair (CHOLMOD/UMFPACK): exactly for
the direct solvers (MUMPS, UMFPACK alone), at most one more per step for GMRES + BoomerAMG and
GAMG (inexact Newton, newton.hpp). The choice is printed and stored in /summary/linear_solver,
and the contact forces agree with the reference to the accuracy the energy criterion leaves.

    check_solver_choice.py --covcontact BIN --deck DECK --reference REF.h5 --scratch DIR
"""
import argparse
import re
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

DIRECT = {"umfpack": "UMFPACK", "mumps": "MUMPS"}
ITERATIVE = {"amg": "GMRES+BoomerAMG", "gamg": "GMRES+GAMG"}


def iterations(path):
    with h5py.File(path, "r") as f:
        steps = sorted(f["steps"].keys())
        return [int(f["steps"][s].attrs["iterations"]) for s in steps]


def total_force(path):
    with h5py.File(path, "r") as f:
        last = sorted(f["steps"].keys())[-1]
        return np.array(f["steps"][last]["contact"]["interface"]["total_force"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--deck", required=True)
    parser.add_argument("--reference", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    scratch = Path(args.scratch)
    scratch.mkdir(parents=True, exist_ok=True)
    deck = Path(args.deck)
    reference = iterations(args.reference)
    reference_force = total_force(args.reference)
    problems = []
    for solver, backend in {**DIRECT, **ITERATIVE}.items():
        text = re.sub(r"^solve\s*$", f"solve solver={solver}", deck.read_text(), flags=re.M)
        # The variant lives in the scratch folder (never beside the deck, in the source tree): its
        # own include and mesh paths made absolute; an include's paths stay relative to it.
        text = re.sub(r'^(include|mesh)(\s+)"([^"/][^"]*)"',
                      lambda m: f'{m[1]}{m[2]}"{(deck.parent / m[3]).resolve()}"', text, flags=re.M)
        variant = scratch / f"{deck.stem}_{solver}.deck"
        variant.write_text(text)
        results = scratch / f"{solver}.h5"
        run = subprocess.run([args.covcontact, "run", str(variant), "-o", str(results),
                              "--threads", "1"], capture_output=True, text=True, timeout=600)
        if run.returncode != 0:
            problems.append(f"{solver}: exit {run.returncode}: {run.stderr[-500:]}")
            continue
        expected_line = f"linear solver: {solver} -> {backend}"
        if expected_line not in run.stdout:
            problems.append(f"{solver}: '{expected_line}' not printed")
        with h5py.File(results, "r") as f:
            logged = f["summary"].attrs["linear_solver"]
            logged = logged.decode() if isinstance(logged, bytes) else str(logged)
        if not logged.startswith(f"{solver} -> {backend}"):
            problems.append(f"{solver}: /summary/linear_solver is '{logged}'")
        counts = iterations(results)
        allowed = 0 if solver in DIRECT else 1
        if len(counts) != len(reference) or any(
                c - r > allowed or c < r for c, r in zip(counts, reference)):
            problems.append(f"{solver}: iterations per step {counts}, reference {reference} "
                            f"(allowed +{allowed} per step)")
        # The energy criterion 1e-16 bounds the force error at ~1e-8 relative (newton.hpp).
        force = total_force(results)
        error = np.linalg.norm(force - reference_force) / np.linalg.norm(reference_force)
        if error > 1e-6:
            problems.append(f"{solver}: contact force differs from the reference by {error:.2e}")
        print(f"{solver}: {backend}, iterations {counts} (reference {reference}), "
              f"force error {error:.1e}")
    for p in problems:
        print("FAILED:", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
