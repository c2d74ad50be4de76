"""CalculiX 2.20 side of the benchmark (issue 8): the example 6.1 mesh from gmsh written as a
CalculiX input deck (C3D8I, face-to-face penalty contact with Coulomb friction, the same loading as
the CovContact deck), and the reading of a finished run (iterations, reaction curve).

Used by scripts/bench.py (which also writes the committed decks in input/performance/calculix/).
"""

import os
import re
import subprocess
import tempfile

# Face k of a C3D8 element (CalculiX/Abaqus numbering) as its local node numbers. gmsh orders the
# nodes of a hexahedron exactly as CalculiX does (bottom 1-4, top 5-8).
C3D8_FACES = {
    1: (0, 1, 2, 3),
    2: (4, 7, 6, 5),
    3: (0, 4, 5, 1),
    4: (1, 5, 6, 2),
    5: (2, 6, 7, 3),
    6: (3, 7, 4, 0),
}

GMSH_HEX8 = 5
GMSH_QUAD4 = 3


def read_msh2(path):
    """Nodes {tag: (x, y, z)}, physical names {tag: name} and elements [(type, physical, nodes)]."""
    with open(path) as stream:
        lines = stream.read().split("\n")
    names, nodes, elements = {}, {}, []
    k = 0
    while k < len(lines):
        line = lines[k].strip()
        if line == "$PhysicalNames":
            count = int(lines[k + 1])
            for row in lines[k + 2:k + 2 + count]:
                dim, tag, name = row.split(maxsplit=2)
                names[int(tag)] = name.strip('"')
            k += 2 + count
        elif line == "$Nodes":
            count = int(lines[k + 1])
            for row in lines[k + 2:k + 2 + count]:
                tag, x, y, z = row.split()
                nodes[int(tag)] = (float(x), float(y), float(z))
            k += 2 + count
        elif line == "$Elements":
            count = int(lines[k + 1])
            for row in lines[k + 2:k + 2 + count]:
                values = [int(v) for v in row.split()]
                kind, tags = values[1], values[2]
                elements.append((kind, values[3], values[3 + tags:]))
            k += 2 + count
        else:
            k += 1
    return nodes, names, elements


def mesh_geo(geo, parameters, msh):
    """Meshes the .geo with gmsh (the mesh CovContact builds from the same parameters)."""
    command = ["gmsh", geo, "-3", "-format", "msh2", "-o", msh]
    for name, value in parameters.items():
        command += ["-setnumber", name, str(value)]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def face_surface(quads, hexes_by_node, hexes):
    """(element, face number) of every boundary quad: the hexahedron holding its four nodes."""
    faces = []
    for quad in quads:
        owners = set(hexes_by_node[quad[0]])
        for node in quad[1:]:
            owners &= set(hexes_by_node[node])
        (element,) = owners
        local = {node: k for k, node in enumerate(hexes[element])}
        corners = {local[node] for node in quad}
        (face,) = [f for f, ids in C3D8_FACES.items() if set(ids) == corners]
        faces.append((element, face))
    return faces


def write_rows(out, values, per_line=8):
    for k in range(0, len(values), per_line):
        out.write(", ".join(str(v) for v in values[k:k + per_line]) + ",\n")


def write_mesh(out, msh, element_type, node_sets, surfaces):
    """The mesh in `msh` as CalculiX's *NODE, *ELEMENT (one set per gmsh volume, named as it),
    *NSET (the nodes of the gmsh surfaces `node_sets`) and *SURFACE (the element faces of the gmsh
    surfaces `surfaces`) blocks."""
    nodes, names, elements = read_msh2(msh)
    hexes, volumes, quads = {}, {}, {}
    for number, (kind, physical, connectivity) in enumerate(elements, start=1):
        if kind == GMSH_HEX8:
            hexes[number] = connectivity
            volumes.setdefault(names[physical], []).append(number)
        elif kind == GMSH_QUAD4:
            quads.setdefault(names[physical], []).append(connectivity)
    hexes_by_node = {}
    for number, connectivity in hexes.items():
        for node in connectivity:
            hexes_by_node.setdefault(node, []).append(number)
    node_set = {name: sorted({n for quad in faces for n in quad}) for name, faces in quads.items()}
    out.write("*NODE\n")
    for tag, (x, y, z) in sorted(nodes.items()):
        out.write(f"{tag}, {x:.12g}, {y:.12g}, {z:.12g}\n")
    for name, numbers in volumes.items():
        out.write(f"*ELEMENT, TYPE={element_type}, ELSET={name}\n")
        for number in numbers:
            out.write(f"{number}, " + ", ".join(str(n) for n in hexes[number]) + "\n")
    for name in node_sets:
        out.write(f"*NSET, NSET={name}\n")
        write_rows(out, node_set[name])
    for name in surfaces:
        out.write(f"*SURFACE, NAME={name}, TYPE=ELEMENT\n")
        for element, face in face_surface(quads[name], hexes_by_node, hexes):
            out.write(f"{element}, S{face}\n")


def write_inp(msh, path, loading):
    """CalculiX deck for example 6.1 on the mesh in `msh`; `loading` as in bench.py's LOADING."""
    with open(path, "w") as out:
        out.write("** Example 6.1 (Konyukhov & Schweizerhof 2005) for CalculiX 2.20, written by\n"
                  "** scripts/bench_calculix.py from the gmsh mesh of meshes/block_on_base.geo\n"
                  "** (the mesh CovContact solves). C3D8I, face-to-face penalty contact.\n")
        write_mesh(out, msh, "C3D8I",
                   ("block_top", "base_bottom", "block_front", "block_back", "base_front",
                    "base_back"), ("block_bottom", "base_top"))
        out.write(MODEL_TEMPLATE.format(**loading))


# Material, contact and the two steps. The slave surface (listed first) is the base top, the
# master the block bottom, as in the CovContact deck. *STATIC, DIRECT keeps the increment fixed:
# one increment for the press, `slide_steps` equal increments for the slide (no automatic
# step control, so that both programs solve the same load increments).
MODEL_TEMPLATE = """\
*MATERIAL, NAME=ELASTIC
*ELASTIC
{young:g}, {poisson:g}
*SOLID SECTION, ELSET=block, MATERIAL=ELASTIC
*SOLID SECTION, ELSET=base, MATERIAL=ELASTIC
*SURFACE INTERACTION, NAME=INTERFACE
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
{eps_n:g}
*FRICTION
{mu:g}, {eps_t:g}
*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=SURFACE TO SURFACE
base_top, block_bottom
*BOUNDARY
base_bottom, 1, 3, 0.
block_front, 3, 3, 0.
block_back, 3, 3, 0.
base_front, 3, 3, 0.
base_back, 3, 3, 0.
*STEP, NLGEOM, INC=1000
*STATIC, DIRECT
1., 1.
*BOUNDARY
block_top, 1, 1, 0.
block_top, 2, 2, {press:g}
*NODE PRINT, NSET=block_top, TOTALS=ONLY
RF
*NODE FILE
U, RF
*CONTACT FILE
CDIS, CSTR
*END STEP
*STEP, NLGEOM, INC=1000
*STATIC, DIRECT
1., {slide_steps:d}.
*BOUNDARY
block_top, 1, 1, {slide:g}
*NODE PRINT, NSET=block_top, TOTALS=ONLY
RF
*NODE FILE
U, RF
*CONTACT FILE
CDIS, CSTR
*END STEP
"""


def read_sta(path):
    """Increments, Newton iterations and cut-backs from CalculiX's .sta file: a row per attempt,
    a failed one marked U after its attempt number (its iterations count too)."""
    increments = iterations = cutbacks = 0
    pattern = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)(U?)\s+(\d+)\s+[-+.\dEe]+")
    with open(path) as stream:
        for line in stream:
            match = pattern.match(line)
            if match:
                failed = match.group(4) == "U"
                cutbacks += failed
                increments += not failed
                iterations += int(match.group(5))
    return {"increments": increments, "iterations": iterations, "cutbacks": cutbacks}


def read_reaction_totals(path):
    """[(time, Fx, Fy, Fz)] of the block_top totals in the .dat file (one per increment)."""
    curve, time = [], None
    header = re.compile(r"total force.*time\s+([-+.\dEe]+)", re.IGNORECASE)
    with open(path) as stream:
        lines = stream.readlines()
    k = 0
    while k < len(lines):
        match = header.search(lines[k])
        if match:
            time = float(match.group(1))
            k += 1
            while k < len(lines) and not lines[k].strip():
                k += 1
            fx, fy, fz = (float(v) for v in lines[k].split()[:3])
            curve.append((time, fx, fy, fz))
        k += 1
    return curve


def write_deck(path, mesh, loading):
    """Meshes meshes/block_on_base.geo with `mesh`'s parameters and writes the deck to `path`."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with tempfile.TemporaryDirectory() as scratch:
        msh = os.path.join(scratch, "mesh.msh")
        mesh_geo(os.path.join(root, "meshes", "block_on_base.geo"), mesh, msh)
        write_inp(msh, path, loading)
