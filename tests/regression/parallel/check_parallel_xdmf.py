"""ParaView check of a results file written by 2 processes together (parallel HDF5), run with
pvbatch after parallel.crossing: the Xdmf3 reader finds every written step of the HDF5 file, and
at each step the displacement range ParaView shows is the range stored in the file (read with
h5py, independently of ParaView).

Usage: pvbatch --force-offscreen-rendering check_parallel_xdmf.py RESULTS.h5
"""
import os
import sys

import h5py
import numpy as np
from paraview.simple import Xdmf3ReaderT


def fail(message):
    print("FAIL " + message)
    sys.exit(1)


def main():
    results = os.path.abspath(sys.argv[1])
    with h5py.File(results, "r") as h5:
        if int(h5.attrs["writing_processes"]) != 2:
            fail(f"{results} was written by {h5.attrs['writing_processes']} processes, not 2")
        steps = sorted(h5["steps"].values(), key=lambda group: group.attrs["step"])
        expected = [(float(g.attrs["time"]), g["displacement"][...]) for g in steps]
    reader = Xdmf3ReaderT(FileName=[results[:-3] + ".xdmf"])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if times != [time for time, _ in expected]:
        fail(f"ParaView has time steps {times[:4]}..., the file {[t for t, _ in expected][:4]}...")
    for time, displacement in expected:
        reader.UpdatePipeline(time)
        for component in range(3):
            shown = list(reader.PointData["displacement"].GetRange(component))
            stored = [float(np.min(displacement[:, component])),
                      float(np.max(displacement[:, component]))]
            if shown != stored:
                fail(f"t = {time} displacement {component}: ParaView {shown}, file {stored}")
    print(f"OK: ParaView loads the 2-process file's {len(times)} steps with the stored "
          "displacements")


if __name__ == "__main__":
    main()
