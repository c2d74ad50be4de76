#!/usr/bin/python3
"""Copy a results file into a small regression reference: what `covcontact compare` reads.

Keeps the root attributes, /summary, /mesh/blocks (names), every step's attributes,
set_reactions and per contact pair total_force and slave_nodal_force; drops displacements,
reactions, restart data and the per-point contact fields, which make a file of ~1 MB.

    /usr/bin/python3 tests/regression/paper/shrink_reference.py RUN.h5 reference/NAME.h5
"""
import sys

import h5py

KEPT_STEP_FIELDS = ["set_reactions"]
KEPT_PAIR_FIELDS = ["total_force", "slave_nodal_force"]


def copy_attributes(source, target):
    for key, value in source.attrs.items():
        target.attrs[key] = value


def shrink(run_path, reference_path):
    with h5py.File(run_path, "r") as run, h5py.File(reference_path, "w") as reference:
        copy_attributes(run, reference)
        for group in ("summary", "mesh"):
            if group in run:
                copy_attributes(run[group], reference.require_group(group))
        if "mesh/blocks" in run:
            copy_attributes(run["mesh/blocks"], reference.require_group("mesh/blocks"))
        for name, step in run["steps"].items():
            target = reference.require_group(f"steps/{name}")
            copy_attributes(step, target)
            for field in KEPT_STEP_FIELDS:
                if field in step:
                    run.copy(step[field], target, name=field)
            for pair_name, pair in step.get("contact", {}).items():
                pair_target = target.require_group(f"contact/{pair_name}")
                copy_attributes(pair, pair_target)
                for field in KEPT_PAIR_FIELDS:
                    if field in pair:
                        run.copy(pair[field], pair_target, name=field)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    shrink(sys.argv[1], sys.argv[2])
