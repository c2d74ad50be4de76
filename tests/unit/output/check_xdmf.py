"""ParaView check of the XDMF sidecar of the round-trip run (run with pvbatch): the Xdmf3 reader
must find every time step, the displacement range and per-block stresses of the synthetic run, the
contact point clouds with one vertex per point, and the Hex27/Hex18 nodes where VTK's own cell
definitions put them.

Usage: pvbatch --force-offscreen-rendering check_xdmf.py ROUNDTRIP_EXPECTED.json
"""
import json
import os
import re
import sys

from paraview.simple import Xdmf3ReaderT
from vtkmodules.vtkCommonDataModel import (VTK_HEXAHEDRON, VTK_POLY_VERTEX,
                                           VTK_TRIQUADRATIC_HEXAHEDRON, vtkHexahedron,
                                           vtkTriQuadraticHexahedron)

# Node positions are computed as origin + edges * (u, v, w): a few ulps of the coordinates.
POSITION_TOLERANCE = 1e-12


def fail(message):
    print("FAIL " + message)
    sys.exit(1)


def blocks_by_name(multiblock):
    """Top-level blocks keyed by grid name (the reader may append "[n]")."""
    blocks = {}
    for index in range(multiblock.GetNumberOfBlocks()):
        name = multiblock.GetMetaData(index).Get(multiblock.NAME())
        blocks[re.sub(r"\[\d+\]$", "", name)] = multiblock.GetBlock(index)
    return blocks


def array_rows(array):
    return [list(array.GetTuple(i)) for i in range(array.GetNumberOfTuples())]


def check_equal(name, actual, expected):
    if actual != expected:
        fail(f"{name}: ParaView has {actual}, expected {expected}")


def check_positions(name, grid, cell_type, parametric, placement):
    """Each node of cell 0 must sit at origin + edges @ VTK's parametric coordinate of that node."""
    check_equal(f"{name} cell type", grid.GetCellType(0), cell_type)
    cell = grid.GetCell(0)
    edges = placement["edges"]  # rows are the columns of the placement matrix
    for local in range(cell.GetNumberOfPoints()):
        uvw = parametric[3 * local:3 * local + 3]
        expected = [placement["origin"][i] + sum(edges[j][i] * uvw[j] for j in range(3))
                    for i in range(3)]
        actual = grid.GetPoint(cell.GetPointId(local))
        if max(abs(a - e) for a, e in zip(actual, expected)) > POSITION_TOLERANCE:
            fail(f"{name} node {local} at {actual}, VTK expects {expected}")


def check_step(reader, step, expected, first_element):
    reader.UpdatePipeline(step["time"])
    blocks = blocks_by_name(reader.GetClientSideObject().GetOutputDataObject(0))
    pairs = [pair for pair, values in step["contact"].items() if len(values["gap"]) > 0]
    check_equal(f"step {step['step']} grids", sorted(blocks),
                sorted(["base", "cap27", "shell18"] + [f"contact {pair}" for pair in pairs]))
    for component in range(3):
        values = [row[component] for row in step["displacement"]]
        actual = reader.PointData["displacement"].GetRange(component)
        check_equal(f"step {step['step']} displacement range {component}", list(actual),
                    [min(values), max(values)])
    for name, first in first_element.items():
        grid = blocks[name]
        stress = array_rows(grid.GetCellData().GetArray("stress"))
        check_equal(f"step {step['step']} {name} stress", stress,
                    step["stress"][first:first + grid.GetNumberOfCells()])
    for pair in pairs:
        cloud, values = blocks[f"contact {pair}"], step["contact"][pair]
        points = len(values["gap"])
        check_equal(f"{pair} points", cloud.GetNumberOfPoints(), points)
        check_equal(f"{pair} vertex cells", cloud.GetNumberOfCells(), points)
        check_equal(f"{pair} cell type", cloud.GetCellType(0), VTK_POLY_VERTEX)
        check_equal(f"{pair} positions", [list(cloud.GetPoint(i)) for i in range(points)],
                    values["position"])
        for field in ("gap", "normal_traction", "state", "edge_share"):
            stored = [row[0] for row in array_rows(cloud.GetPointData().GetArray(field))]
            check_equal(f"{pair} {field}", stored, [float(v) for v in values[field]])
        check_equal(f"{pair} tangential_traction",
                    array_rows(cloud.GetPointData().GetArray("tangential_traction")),
                    values["tangential_traction"])
    return blocks


def main():
    with open(sys.argv[1]) as stream:
        expected = json.load(stream)
    reader = Xdmf3ReaderT(FileName=[os.path.abspath(expected["xdmf"])])
    reader.UpdatePipelineInformation()
    times = [step["time"] for step in expected["steps"]]
    check_equal("time steps", list(reader.TimestepValues), times)
    first_element = {"base": 0, "cap27": 4, "shell18": 5}
    for step in expected["steps"]:
        blocks = check_step(reader, step, expected, first_element)
    hex27 = vtkTriQuadraticHexahedron()
    check_positions("cap27 (Hex27)", blocks["cap27"], VTK_TRIQUADRATIC_HEXAHEDRON,
                    [hex27.GetParametricCoords()[i] for i in range(81)],
                    expected["placements"]["cap27"])
    hex8 = vtkHexahedron()
    check_positions("shell18 (Hex18 corners)", blocks["shell18"], VTK_HEXAHEDRON,
                    [hex8.GetParametricCoords()[i] for i in range(24)],
                    expected["placements"]["shell18"])
    print(f"OK: ParaView's Xdmf3 reader loads {len(times)} time steps with the expected "
          "displacements, stresses, contact point clouds and Hex27/Hex18 node positions")


if __name__ == "__main__":
    main()
