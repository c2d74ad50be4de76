#!/usr/bin/python3
"""Contact pressure at the slab's top side edges against its middle, for ironing results files
(issue 14, docs/verification/sliding.md, forty-eighth session): how the refined drags' trouble
spot, the slab's side edges under the die, loads up as the mesh is refined.

usage: ironing_edge_pressure.py RESULTS.h5:H [...] [--times 0.1,0.2,0.21] [--pair die]

H is the depth of the slab's elements (0.5 for the committed decks, 0.25 refined twice). For
each stored step at one of --times it prints the largest normal contact pressure |N| among the
closed points within 0.3 of the slab's sides (y = 0 and y = 4) and among those within 0.5 of
its middle (y = 2), and the deepest penetration at the sides as a share of H.
"""
import argparse
import os

# Read-only, possibly while the run still writes: no file lock.
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
import h5py  # noqa: E402
import numpy as np  # noqa: E402

SLAB_WIDTH = 4.0
SIDE_BAND = 0.3
MIDDLE_BAND = 0.5


def edge_and_middle(step, pair):
    """(largest |N| at the sides, deepest gap at the sides, largest |N| in the middle)."""
    contact = step["contact"][pair]
    normal = contact["normal_traction"][:]
    gap = contact["gap"][:]
    y = contact["position"][:, 1]
    closed = normal < 0
    side = closed & (np.minimum(y, SLAB_WIDTH - y) < SIDE_BAND)
    middle = closed & (np.abs(y - SLAB_WIDTH / 2) < MIDDLE_BAND)
    if not side.any() or not middle.any():
        return None
    return -normal[side].min(), gap[side].min(), -normal[middle].min()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", nargs="+", help="RESULTS.h5:H (H: the slab's element depth)")
    parser.add_argument("--times", default="0.1,0.2,0.21")
    parser.add_argument("--pair", default="die")
    args = parser.parse_args()
    times = [float(t) for t in args.times.split(",")]
    print("| results | t | h | sides: max pressure | sides: deepest penetration / h | "
          "middle: max pressure |")
    print("|---|---|---|---|---|---|")
    for item in args.results:
        path, depth = item.rsplit(":", 1)
        depth = float(depth)
        with h5py.File(path, "r") as f:
            for name in sorted(f["steps"].keys()):
                step = f["steps"][name]
                time = float(step.attrs["time"])
                if not any(abs(time - t) < 1e-9 for t in times):
                    continue
                found = edge_and_middle(step, args.pair)
                if found is None:
                    continue
                side, deepest, middle = found
                print(f"| {os.path.basename(path)} | {time:g} | {depth:g} | {side:.2f} | "
                      f"{-100 * deepest / depth:.0f} % | {middle:.2f} |")


if __name__ == "__main__":
    main()
