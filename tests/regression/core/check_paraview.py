"""ParaView check of a real run's XDMF sidecar (run with pvbatch --force-offscreen-rendering):
ParaView's Xdmf3 reader, given the absolute path of RUN.xdmf, must find the time steps of RUN.h5
and, at every step, the displacement range (per component) and the stress range that h5py reads
from the same file. The approach of tests/unit/output/check_xdmf.py, on a run of the command.

Usage: pvbatch --force-offscreen-rendering check_paraview.py RUN.h5
"""
import os
import sys

import h5py  # pvbatch runs Debian's python3, which has h5py


def fail(message):
    print("FAIL " + message)
    sys.exit(1)


def expected_steps(path):
    """[(time, per-component (min, max) of displacement and of stress)] of every step group."""
    steps = []
    with h5py.File(path, "r") as h5:
        for name in sorted(h5["steps"].keys()):
            group = h5["steps"][name]
            ranges = {}
            for field in ("displacement", "stress"):
                values = group[field][...]
                ranges[field] = [[values[:, c].min(), values[:, c].max()]
                                 for c in range(values.shape[1])]
            steps.append((float(group.attrs["time"]), ranges))
    return steps


def main():
    results = os.path.abspath(sys.argv[1])
    steps = expected_steps(results)
    if not steps:
        fail(f"{results} has no steps")
    # Imported after h5py has closed the file: ParaView brings its own HDF5 library.
    from paraview.simple import Xdmf3ReaderT

    reader = Xdmf3ReaderT(FileName=[results[:-len(".h5")] + ".xdmf"])
    reader.UpdatePipelineInformation()
    times = [time for time, _ in steps]
    if list(reader.TimestepValues) != times:
        fail(f"ParaView finds time steps {list(reader.TimestepValues)}, the file has {times}")
    for time, ranges in steps:
        reader.UpdatePipeline(time)
        for field, data in (("displacement", reader.PointData), ("stress", reader.CellData)):
            for component, expected in enumerate(ranges[field]):
                actual = list(data[field].GetRange(component))
                if actual != expected:
                    fail(f"t = {time}: {field} range {component} is {actual} in ParaView, "
                         f"{expected} in the file")
    largest = max(abs(value) for _, ranges in steps for pair in ranges["displacement"]
                  for value in pair)
    print(f"OK: ParaView's Xdmf3 reader loads the {len(times)} time steps of {results} with the "
          f"displacement and stress ranges of the file (largest |u| component {largest:.6g})")


if __name__ == "__main__":
    main()
