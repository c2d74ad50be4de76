#!/usr/bin/python3
"""The include graph of src/ follows the layers of docs/architecture.md: a module may include its
own headers and those of modules on lower layers, never a module on its own layer or above.

Data flows deck -> spec -> model -> stepper -> Newton -> assembler -> linear solver -> output;
the includes point the other way round where the caller owns an interface (the solver defines
NonlinearProblem, the model implements it), so the rule is stated on layers, not on the flow.
Exit 1 lists every backward include with file:line.
"""
import re
import sys
from pathlib import Path

ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else Path(__file__).resolve().parents[2]

# Lowest first. Modules on one layer are independent of each other.
LAYERS = [
    ["common"],                              # errors, source locations, name matching
    ["spec", "records"],                     # plain data: ProblemSpec in, result records out
    ["deck", "materials", "fem"],            # deck language; constitutive laws; dofs/assembly
    ["mesh"],                                # gmsh import, node and face sets
    ["elements", "contact"],                 # element and contact kernels
    ["solver", "output"],                    # Newton, stepping, linear solvers; HDF5/XDMF/CSV
    ["parallel"],                            # PETSc/MPI backend plugin behind LinearSolver
    ["model"],                               # ProblemSpec + mesh -> the runtime model
    ["verification"],                        # analytic references, reports
    ["app"],                                 # the covcontact command
]
LAYER = {module: level for level, modules in enumerate(LAYERS) for module in modules}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def self_test():
    """The check must fail on a backward include: a copy of the layer rule applied to a tiny tree."""
    import tempfile
    global ROOT
    with tempfile.TemporaryDirectory() as tmp:
        ROOT = Path(tmp)
        for module in LAYER:
            (ROOT / "src" / module).mkdir(parents=True)
        (ROOT / "src/contact/pair.hpp").write_text('#include "fem/a.hpp"\n#include "output/w.hpp"\n')
        (ROOT / "src/spec/s.hpp").write_text('#include "common/e.hpp"\n#include "deck/p.hpp"\n')
        problems = find_problems()
    expected = ["src/contact/pair.hpp:2:", "src/spec/s.hpp:2:"]
    ok = len(problems) == 2 and all(p.startswith(e) for p, e in zip(sorted(problems), expected))
    print("check_layering --self-test:", "ok" if ok else f"FAILED, found {problems}")
    return 0 if ok else 1


def main():
    if "--self-test" in sys.argv:
        return self_test()
    problems = find_problems()
    modules = sorted(p.name for p in (ROOT / "src").iterdir() if p.is_dir())
    for document in ("README.md", "docs/architecture.md"):
        text = (ROOT / document).read_text()
        for module in modules:
            if f"src/{module}" not in text:
                problems.append(f"{document}: module src/{module} is not described")
    for problem in problems:
        print(problem)
    print(f"check_layering: {len(modules)} modules, {len(problems)} backward or unknown includes")
    return 1 if problems else 0


def find_problems():
    problems = []
    modules = sorted(p.name for p in (ROOT / "src").iterdir() if p.is_dir())
    for module in modules:
        if module not in LAYER:
            problems.append(f"src/{module}/: module not placed in a layer (tests/structure/"
                            "check_layering.py and docs/architecture.md)")
    for path in sorted((ROOT / "src").rglob("*.[ch]pp")):
        module = path.relative_to(ROOT / "src").parts[0]
        if module not in LAYER:
            continue
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = INCLUDE.match(line)
            if not match or match.group(1) == module:
                continue
            target = match.group(1)
            if target not in LAYER:
                problems.append(f"{path.relative_to(ROOT)}:{number}: includes unknown module '{target}'")
            elif LAYER[target] >= LAYER[module]:
                problems.append(f"{path.relative_to(ROOT)}:{number}: {module} (layer {LAYER[module]}) "
                                f"includes {target} (layer {LAYER[target]}): only lower layers may be "
                                "included")
    return problems


if __name__ == "__main__":
    sys.exit(main())
