"""Shared helpers of the issue-2 command tests (run with /usr/bin/python3): the common command line
(--covcontact BINARY --decks DIR --scratch DIR), running `covcontact` in a scratch directory, and
reading its results (HDF5 with h5py, reactions CSV, XDMF references).
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import progress_lines  # noqa: E402  (tests/support)
from script_checks import check  # noqa: E402  (tests/support)

# Longest time one command of these tests may take on a loaded 2-core machine.
COMMAND_TIMEOUT_S = 100


def parse_arguments(description, extra=None):
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--covcontact", required=True, help="the covcontact binary")
    parser.add_argument("--decks", required=True, help="input/verification/core")
    parser.add_argument("--scratch", required=True, help="working directory (emptied first)")
    if extra:
        extra(parser)
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    return args


def run(command, cwd):
    """Runs a command to completion; returns the CompletedProcess (text stdout and stderr)."""
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True,
                          timeout=COMMAND_TIMEOUT_S)


def step_lines(stdout):
    """The plain progress lines `step k  t = T of END  N iterations ...` as {k: iterations}."""
    return progress_lines.converged_steps(stdout)


def read_reactions_csv(path):
    """Header and rows of a reactions CSV; numbers parsed as Python floats (exact: 17 digits)."""
    with open(path, newline="") as stream:
        rows = list(csv.reader(stream))
    return rows[0], [[float(value) for value in row] for row in rows[1:]]


def xdmf_references(path):
    """(time, [HDF5 file:path references]) per time step of an XDMF temporal collection."""
    root = ElementTree.parse(path).getroot()
    steps = []
    for grid in root.findall("Domain/Grid/Grid"):
        time = float(grid.find("Time").get("Value"))
        references = [item.text.strip() for item in grid.iter("DataItem")
                      if item.get("Format") == "HDF"]
        steps.append((time, references))
    return steps


def step_names(h5):
    """Names of the step groups, checked to be 000001, 000002, ... without gaps."""
    names = sorted(h5["steps"].keys())
    check(names == ["%06d" % (index + 1) for index in range(len(names))],
          f"step groups are not 1..{len(names)} without gaps: {names}")
    return names
