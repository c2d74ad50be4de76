#!/usr/bin/python3
"""Every Python module and external program the test suite and scripts use must come from a
Debian package that scripts/install-deps.sh installs (directly or as a dependency).

A fresh machine has only the base image. A package installed by hand on a developer's or CI's
machine makes a test pass there and fail on a fresh one (issue 12: python3-paraview, a mere
Recommends of paraview). This check derives what is used from the sources themselves:
  - `import X` / `from X import` in every .py file under tests/ and scripts/ (parsed with ast,
    so docstrings do not count), except the standard library and the project's own modules;
  - `find_program(VAR name)` in every CMakeLists.txt and .cmake file;
  - the interpreter /usr/bin/python3 itself.
Each is resolved to the file that provides it and `dpkg -S` names the owning package, which
must lie in the dependency closure (Depends and Pre-Depends, not Recommends) of the packages
listed in install-deps.sh. Exit 1 names every module or program and the package to add.
"""
import ast
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else Path(__file__).resolve().parents[2]


def listed_packages():
    text = (ROOT / "scripts" / "install-deps.sh").read_text()
    block = re.search(r"^packages=\((.*?)^\)", text, re.S | re.M)
    if not block:
        sys.exit("check_dependencies: no packages=( ... ) array in scripts/install-deps.sh")
    words = []
    for line in block.group(1).splitlines():
        words += line.split("#", 1)[0].split()
    return set(words)


def installed_graph():
    """package -> list of dependency alternatives (each a list of names); virtual -> providers."""
    out = subprocess.run(
        ["dpkg-query", "-W", "-f", "${Package}\t${Status}\t${Pre-Depends}, ${Depends}\t${Provides}\n"],
        capture_output=True, text=True, check=True).stdout
    depends, providers = {}, {}
    for line in out.splitlines():
        name, status, deps, provides = (line.split("\t") + ["", "", ""])[:4]
        if "installed" not in status.split():
            continue
        alternatives = []
        for clause in deps.split(","):
            names = [re.sub(r"[\s(:].*", "", a.strip()) for a in clause.split("|")]
            names = [n for n in names if n]
            if names:
                alternatives.append(names)
        depends[name] = alternatives
        for p in provides.split(","):
            p = re.sub(r"[\s(:].*", "", p.strip())
            if p:
                providers.setdefault(p, []).append(name)
    return depends, providers


def closure(roots, depends, providers):
    seen, todo = set(), list(roots)
    while todo:
        name = todo.pop()
        for real in [name] if name in depends else providers.get(name, []):
            if real in seen:
                continue
            seen.add(real)
            for alternatives in depends.get(real, []):
                todo += [a for a in alternatives if a in depends or a in providers]
    return seen


def owning_package(path):
    result = subprocess.run(["dpkg", "-S", str(Path(path).resolve())], capture_output=True, text=True)
    if result.returncode != 0:  # e.g. /usr/bin/x -> /bin/x on a merged-/usr system
        result = subprocess.run(["dpkg", "-S", str(path)], capture_output=True, text=True)
    if result.returncode != 0:
        return None
    return result.stdout.split(":", 1)[0].split(",")[0].strip()


def python_imports():
    """(module, first file importing it) for non-stdlib, non-project imports."""
    local = set()
    for d in ("tests", "scripts"):
        for p in (ROOT / d).rglob("*.py"):
            local.add(p.stem)
            local.add(p.parent.name)  # packages of the project's own (a folder of modules)
    found = {}
    for d in ("tests", "scripts"):
        for path in sorted((ROOT / d).rglob("*.py")):
            if "corpus" in path.parts:
                continue
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                names = []
                if isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                    names = [node.module]
                for name in names:
                    top = name.split(".")[0]
                    if top in sys.stdlib_module_names or top in local:
                        continue
                    found.setdefault(top, path.relative_to(ROOT))
    return found


def cmake_programs():
    found = {}
    files = [ROOT / "CMakeLists.txt"] + sorted(ROOT.glob("src/**/CMakeLists.txt")) + \
        sorted(ROOT.glob("tests/**/CMakeLists.txt")) + sorted(ROOT.glob("tests/**/*.cmake"))
    for path in files:
        for match in re.finditer(r"(?:find_program|cc_require_program)\(\s*\w+\s+(?:NAMES\s+)?([\w.+-]+)", path.read_text()):
            found.setdefault(match.group(1), path.relative_to(ROOT))
    return found


def self_test():
    """The check must fail when install-deps.sh lacks a package a test needs: drop
    python3-paraview from a copy of the list and expect it to be named."""
    import shutil as sh
    import tempfile
    global ROOT
    source = ROOT
    with tempfile.TemporaryDirectory() as tmp:
        ROOT = Path(tmp)
        for d in ("tests", "scripts"):
            sh.copytree(source / d, ROOT / d)
        sh.copy(source / "CMakeLists.txt", ROOT / "CMakeLists.txt")
        deps = ROOT / "scripts" / "install-deps.sh"
        deps.write_text(re.sub(r"\bpython3-paraview\b", "", deps.read_text()))
        problems = find_problems()
    ok = any("'python3-paraview'" in p and "paraview" in p for p in problems)
    print("check_dependencies --self-test:", "ok" if ok else f"FAILED, found {problems}")
    return 0 if ok else 1


def main():
    if "--self-test" in sys.argv:
        return self_test()
    problems = find_problems()
    for problem in problems:
        print("MISSING:", problem)
    modules, programs = python_imports(), cmake_programs()
    print(f"check_dependencies: {len(modules)} Python modules ({', '.join(sorted(modules))}) and "
          f"{len(programs)} programs ({', '.join(sorted(programs))}) checked against "
          f"{len(listed_packages())} packages listed in scripts/install-deps.sh")
    return 1 if problems else 0


def find_problems():
    listed = listed_packages()
    depends, providers = installed_graph()
    provided = closure(listed, depends, providers)
    problems = []

    def check(what, where, path, guess):
        if path is None:
            problems.append(f"{what} (used in {where}) is not installed at all; "
                            f"add its Debian package (probably {guess}) to scripts/install-deps.sh")
            return
        package = owning_package(path)
        if package is None:
            problems.append(f"{what} (used in {where}) resolves to {path}, which no Debian package "
                            "owns: it was installed by hand; use a Debian package instead")
        elif package not in provided:
            problems.append(f"{what} (used in {where}) comes from Debian package '{package}', which "
                            "scripts/install-deps.sh does not install (nor anything it depends on): "
                            f"add '{package}' to its package list")

    for module, where in sorted(python_imports().items()):
        spec = importlib.util.find_spec(module)
        origin = None
        if spec is not None:
            origin = spec.origin if spec.origin not in (None, "namespace") else \
                next(iter(spec.submodule_search_locations or []), None)
        check(f"Python module '{module}'", where, origin, f"python3-{module.lower()}")
    for program, where in sorted(cmake_programs().items()):
        check(f"program '{program}'", where, shutil.which(program), program)
    check("interpreter /usr/bin/python3", "tests and scripts", "/usr/bin/python3", "python3")
    return problems


if __name__ == "__main__":
    sys.exit(main())
