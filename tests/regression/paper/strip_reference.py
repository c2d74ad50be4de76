#!/usr/bin/python3
"""Shrink a results file into a regression reference: keep what `covcontact compare` reads.

Copies RUN.h5 to REFERENCE.h5 without the per-node and per-point arrays of the steps
(displacement, reaction, stress, the restart data, and every contact dataset but total_force);
attributes, the mesh, set_reactions, contact total forces, /convergence, /cutbacks and /summary
stay.

    /usr/bin/python3 strip_reference.py build/.../NAME.h5 reference/NAME.h5
"""
import sys

import h5py

NODAL_FIELDS = {"displacement", "reaction", "stress", "restart"}
KEPT_CONTACT_FIELDS = {"total_force"}


def copy_attributes(source, target):
    for key, value in source.attrs.items():
        target.attrs[key] = value


def copy_step(step, target):
    copy_attributes(step, target)
    for name, item in step.items():
        if name in NODAL_FIELDS:
            continue
        if name != "contact":
            step.copy(item, target, name=name)
            continue
        contact = target.create_group("contact")
        copy_attributes(item, contact)
        for pair_name, pair in item.items():
            kept = contact.create_group(pair_name)
            copy_attributes(pair, kept)
            for field in KEPT_CONTACT_FIELDS & set(pair):
                pair.copy(pair[field], kept, name=field)


def main(run, reference):
    with h5py.File(run, "r") as source, h5py.File(reference, "w", libver=("v108", "v108")) as target:
        copy_attributes(source, target)
        for name, item in source.items():
            if name != "steps":
                source.copy(item, target, name=name)
                continue
            steps = target.create_group("steps")
            copy_attributes(item, steps)
            for step_name, step in item.items():
                copy_step(step, steps.create_group(step_name))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
