#!/usr/bin/python3
"""h5py check of the round-trip run written by test_output (RoundTrip.*): every stored number must
equal the expected value in roundtrip_expected.json exactly; the CSV rows must carry the same
numbers; every HDF5 reference in the XDMF sidecar must exist with the declared dimensions.

Usage: check_roundtrip.py ROUNDTRIP_EXPECTED.json
"""
import csv
import json
import sys
import xml.etree.ElementTree as ElementTree

import h5py
import numpy as np

CONTACT_FIELDS = ["position", "gap", "normal_traction", "tangential_traction", "state",
                  "slip_increment", "accumulated_slip", "weight", "edge_share", "total_force",
                  "slave_nodes", "slave_nodal_force"]
CONVERGENCE_FIELDS = ["step", "attempt", "iteration", "time", "residual", "relative_residual",
                      "energy", "relative_energy", "wall_seconds"]


def expect_equal(name, stored, expected):
    stored = np.asarray(stored)
    expected = np.asarray(expected, dtype=stored.dtype)
    if expected.size == 0:
        expected = expected.reshape(stored.shape)
    if stored.shape != expected.shape or not np.array_equal(stored, expected):
        sys.exit(f"FAIL {name}: stored {stored.shape} {stored.ravel()[:6]} != expected "
                 f"{expected.shape} {expected.ravel()[:6]}")


def check_hdf5(h5, expected):
    expect_equal("deck_text", [h5.attrs["deck_text"]], [expected["deck_text"]])
    expect_equal("command_line", [h5.attrs["command_line"]], [expected["command_line"]])
    expect_equal("/mesh/coordinates", h5["mesh/coordinates"], expected["coordinates"])
    for step in expected["steps"]:
        group = h5["steps/%06d" % step["step"]]
        for attribute in ("time", "iterations", "cutbacks"):
            expect_equal(f"{group.name}@{attribute}", group.attrs[attribute], step[attribute])
        for field in ("displacement", "reaction", "stress", "set_reactions"):
            expect_equal(f"{group.name}/{field}", group[field], step[field])
        expect_equal(f"{group.name}/set_reactions@names",
                     list(group["set_reactions"].attrs["names"]), step["set_reaction_names"])
        for pair, values in step["contact"].items():
            for field in CONTACT_FIELDS:
                expect_equal(f"{group.name}/contact/{pair}/{field}",
                             group["contact"][pair][field], values[field])
    table = h5["convergence"]
    if len(table) != len(expected["convergence"]):
        sys.exit(f"FAIL /convergence has {len(table)} rows, expected {len(expected['convergence'])}")
    for column, field in enumerate(CONVERGENCE_FIELDS):
        expect_equal(f"/convergence[{field}]", table[field],
                     [row[column] for row in expected["convergence"]])


def check_csv(path, expected):
    with open(path, newline="") as stream:
        rows = list(csv.reader(stream))
    header, data = rows[0], rows[1:]
    if len(data) != len(expected["steps"]):
        sys.exit(f"FAIL {path}: {len(data)} rows for {len(expected['steps'])} steps")
    for row, step in zip(data, expected["steps"]):
        values = dict(zip(header, (float(cell) for cell in row)))
        wanted = {"step": step["step"], "time": step["time"], "iterations": step["iterations"]}
        for name, force in zip(step["set_reaction_names"], step["set_reactions"]):
            wanted.update({f"{name}_F{axis}": force[i] for i, axis in enumerate("xyz")})
        for pair, contact in step["contact"].items():
            wanted.update({f"contact_{pair}_F{axis}": contact["total_force"][i]
                           for i, axis in enumerate("xyz")})
        if set(values) != set(wanted):
            sys.exit(f"FAIL {path}: columns {sorted(values)} != {sorted(wanted)}")
        for name, value in wanted.items():
            expect_equal(f"{path} step {step['step']} {name}", values[name], value)


def check_xdmf(path, h5, expected):
    root = ElementTree.parse(path).getroot()
    temporal = root.find("Domain/Grid")
    steps = temporal.findall("Grid")
    times = [float(grid.find("Time").get("Value")) for grid in steps]
    expect_equal("XDMF times", times, [step["time"] for step in expected["steps"]])
    references = 0
    for item in root.iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        location = item.text.strip().split(":", 1)[1]
        dataset_path, _, slab = location.partition("|")
        declared = [int(n) for n in item.get("Dimensions").split()]
        dataset = h5[dataset_path]
        if slab:  # Xdmf3 inline hyperslab "start:stride:count:dims"
            start, stride, count, dims = (list(map(int, part.split())) for part in slab.split(":"))
            expect_equal(f"{location} full dims", dims, dataset.shape)
            expect_equal(f"{location} count", count, declared)
        else:
            expect_equal(f"{location} dims", list(dataset.shape), declared)
        references += 1
    print(f"XDMF: {len(steps)} steps, {references} HDF5 references checked")


def main():
    with open(sys.argv[1]) as stream:
        expected = json.load(stream)
    with h5py.File(expected["h5"], "r") as h5:
        check_hdf5(h5, expected)
        check_xdmf(expected["xdmf"], h5, expected)
    check_csv(expected["csv"], expected)
    print(f"OK: {len(expected['steps'])} steps and {len(expected['convergence'])} convergence "
          "rows read back exactly with h5py")


if __name__ == "__main__":
    main()
