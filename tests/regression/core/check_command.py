#!/usr/bin/python3
"""Exit codes and messages of the `covcontact` command:
- `--help` lists exactly the exit codes of src/common/errors.hpp, each with a description;
- no subcommand: 1; `check` of a valid deck: 0 and no file written anywhere; `check` of a deck
  with a misspelt keyword: 2 with file:line and a suggestion;
- `compare` of a run with itself: 0; with the run of a 1 % larger tip displacement
  (neohooke_bending_perturbed.deck): 5 and a diff whose rows name the step, field and set
  component and quote both values exactly as the two files hold them; with a missing file: 6.

Usage: check_command.py --covcontact BIN --decks input/verification/core --scratch DIR
"""
import os
import re
import sys

import h5py

from core_command import check, parse_arguments, run

SOURCE_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(SOURCE_DIR, "scripts"))
import results_file  # noqa: E402
ERRORS_HEADER = os.path.join(SOURCE_DIR, "src", "common", "errors.hpp")
EXIT_OK, EXIT_USAGE, EXIT_INPUT, EXIT_MISMATCH, EXIT_IO = 0, 1, 2, 5, 6
STEPS = 4
COMPONENTS = "xyz"
DIFF_ROW = re.compile(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$")
# A deck with a misspelt keyword on line BAD_LINE.
BAD_DECK = """# misspelt keyword below
title "bad"
materal rubber neohooke E=1e3 nu=0.3
solve
  steps 1 dt=1
end
"""
BAD_LINE = 3
# The relative difference is printed with 4 significant digits.
PRINTED_DIGITS_TOLERANCE = 1e-3


def declared_exit_codes():
    with open(ERRORS_HEADER) as stream:
        return sorted(int(code) for code in re.findall(r"kExit\w+\s*=\s*(\d+)", stream.read()))


def check_help(covcontact, scratch):
    result = run([covcontact, "--help"], scratch)
    check(result.returncode == EXIT_OK, f"--help exit {result.returncode}")
    check("Exit codes:" in result.stdout, "--help has no 'Exit codes:' section")
    section = result.stdout.split("Exit codes:", 1)[1]
    listed = {int(match[0]): match[1] for match in re.findall(r"^\s*(\d+)\s+(\S.*)$", section,
                                                                re.MULTILINE)}
    check(sorted(listed) == declared_exit_codes(),
          f"--help lists exit codes {sorted(listed)}, errors.hpp declares {declared_exit_codes()}")
    result = run([covcontact], scratch)
    check(result.returncode == EXIT_USAGE, f"no subcommand: exit {result.returncode}")


def directory_listing(path):
    return sorted(os.listdir(path))


def check_check(covcontact, decks, scratch):
    empty = os.path.join(scratch, "check")
    os.makedirs(empty)
    deck_directory_before = directory_listing(decks)
    result = run([covcontact, "check", os.path.join(decks, "neohooke_bending.deck")], empty)
    check(result.returncode == EXIT_OK and "valid" in result.stdout,
          f"check of a valid deck: exit {result.returncode}\n{result.stdout}{result.stderr}")
    check(directory_listing(empty) == [], f"check wrote {directory_listing(empty)}")
    check(directory_listing(decks) == deck_directory_before, "check wrote into the deck directory")

    bad = os.path.join(scratch, "bad.deck")
    with open(bad, "w") as stream:
        stream.write(BAD_DECK)
    result = run([covcontact, "check", bad], empty)
    check(result.returncode == EXIT_INPUT, f"check of a bad deck: exit {result.returncode}")
    check(f"bad.deck:{BAD_LINE}:" in result.stderr and "did you mean 'material'" in result.stderr,
          f"bad deck message lacks file:line or the suggestion: {result.stderr}")
    check(directory_listing(empty) == [], f"check of a bad deck wrote {directory_listing(empty)}")


def run_deck(covcontact, decks, scratch, deck, results):
    result = run([covcontact, "run", "-q", os.path.join(decks, deck), "-o", results], scratch)
    check(result.returncode == EXIT_OK, f"run {deck}: exit {result.returncode}\n{result.stderr}")
    return os.path.join(scratch, results)


def set_reaction(path, step, index):
    """Value of set_reactions at `set.component` in a step of a results file."""
    set_name, component = index.rsplit(".", 1)
    with h5py.File(path, "r") as h5:
        return float(results_file.set_reaction(h5["steps"]["%06d" % step],
                                               set_name)[COMPONENTS.index(component)])


def check_compare(covcontact, decks, scratch):
    original = run_deck(covcontact, decks, scratch, "neohooke_bending.deck", "original.h5")
    perturbed = run_deck(covcontact, decks, scratch, "neohooke_bending_perturbed.deck",
                         "perturbed.h5")
    result = run([covcontact, "compare", original, original], scratch)
    check(result.returncode == EXIT_OK and "MATCH" in result.stdout,
          f"compare with itself: exit {result.returncode}\n{result.stdout}")

    result = run([covcontact, "compare", original, perturbed], scratch)
    check(result.returncode == EXIT_MISMATCH,
          f"compare with the perturbed run: exit {result.returncode}\n{result.stdout}")
    rows = [DIFF_ROW.match(line).groups() for line in result.stdout.splitlines()
            if DIFF_ROW.match(line)]
    count = re.search(r"MISMATCH: (\d+) difference", result.stdout)
    check(count and int(count.group(1)) == len(rows) > 0,
          f"the diff lists {len(rows)} rows, the verdict says {count and count.group(1)}")
    check({int(row[0]) for row in rows} == set(range(1, STEPS + 1)),
          f"the diff does not cover every step: {result.stdout}")
    for step, field, index, run_value, reference_value, relative in rows:
        check(field == "set_reactions", f"unexpected field {field}")
        expected_run = set_reaction(original, int(step), index)
        expected_reference = set_reaction(perturbed, int(step), index)
        check(float(run_value) == expected_run and float(reference_value) == expected_reference,
              f"step {step} {index}: diff quotes {run_value} / {reference_value}, the files "
              f"hold {expected_run!r} / {expected_reference!r}")
        exact = abs(expected_run - expected_reference) / max(abs(expected_run),
                                                             abs(expected_reference))
        check(abs(float(relative) - exact) <= PRINTED_DIGITS_TOLERANCE * exact,
              f"step {step} {index}: relative difference {relative}, exact {exact:.6g}")

    result = run([covcontact, "compare", original, os.path.join(scratch, "missing.h5")], scratch)
    check(result.returncode == EXIT_IO and "missing.h5" in result.stderr,
          f"compare with a missing file: exit {result.returncode}\n{result.stderr}")
    return len(rows)


def main():
    args = parse_arguments(__doc__)
    check_help(args.covcontact, args.scratch)
    check_check(args.covcontact, args.decks, args.scratch)
    differences = check_compare(args.covcontact, args.decks, args.scratch)
    print(f"OK: --help lists the {len(declared_exit_codes())} exit codes of errors.hpp; "
          "usage 1; check 0 without files, 2 with file:line for a misspelt keyword; compare 0 "
          f"with itself, 5 with {differences} exact diff rows for a 1 % larger load, 6 for a "
          "missing file")


if __name__ == "__main__":
    main()
