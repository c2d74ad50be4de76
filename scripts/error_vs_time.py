#!/usr/bin/python3
"""Error against run time for CovContact's contact verification cases (issue 6).

Runs the verification decks of input/verification/contact (Hertz sphere and cylinder,
Cattaneo-Mindlin sphere and cylinder, contact patch tests, penalty convergence, and the paper's
example 6.1(a) in a frozen copy, sliding_block_6_1a.deck) over mesh levels, load-step counts and
penalties, reads the errors each run stores in /verification of its results file (for example
6.1: the contact force history against a finer reference run), and writes
docs/verification/accuracy.md with tables, observed orders and log-log plots of error against
run time per contact kind.

Usage (from anywhere; runs one deck at a time, niced, on one thread):
    /usr/bin/python3 scripts/error_vs_time.py                 # run what is missing, then report
    /usr/bin/python3 scripts/error_vs_time.py --cases hertz_rigid_sphere,patch
    /usr/bin/python3 scripts/error_vs_time.py --report-only   # tables and plots from the cache

Finished runs are cached in WORK/results.json (default build-verif/accuracy), so an interrupted
sweep continues where it stopped. Run times: each deck runs with --threads 1 under `nice`; the
CPU time of the child (user + system) is what a dedicated core would take and is the time axis
of the plots, because the machine is shared and wall time there mostly measures the other jobs.
Both are in the tables.
"""
import argparse
import hashlib
import json
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

import h5py

import accuracy_report

ROOT = Path(__file__).resolve().parent.parent
DECKS = ROOT / "input" / "verification" / "contact"
# A frozen copy of input/paper/sliding_block_6_1a.deck, so the sweep's history does not move
# when the paper decks change.
PAPER_DECK = DECKS / "sliding_block_6_1a.deck"
MESHES = ROOT / "meshes"
ELASTIC_MODULUS = 1000.0  # E of every verification deck
ZONE_HALF_SIZE = 1.5      # c of meshes/indented_block.geo in the decks
EXAMPLE_BLOCK_LENGTH = 20.0  # the block of example 6.1 (meshes/block_on_base.geo)


class Variant:
    """One run: a deck with changed mesh parameters, penalties, step counts or contact line."""

    def __init__(self, case, sweep, label, deck, mesh=None, eps_scale=1.0, eps_t_scale=None,
                 steps_scale=None, points=None, replace=(), value=None):
        self.case, self.sweep, self.label, self.deck = case, sweep, label, Path(deck)
        self.mesh = mesh or {}
        self.eps_scale = eps_scale
        self.eps_t_scale = eps_scale if eps_t_scale is None else eps_t_scale
        self.steps_scale = steps_scale  # list: multiplier of the step count per phase
        self.points = points
        self.replace = list(replace)
        self.value = value  # the swept parameter's value (table column, plot abscissa)

    @property
    def target(self):
        """The mesh level of the deck as committed (its accuracy targets are stated for it)."""
        if self.sweep != "mesh":
            return False
        keys = [key for key in ("m", "nl", "nx") if key in self.mesh]
        return bool(keys) and str(self.mesh[keys[0]]) == mesh_default(self.deck, keys[0])

    @property
    def name(self):
        return f"{self.case}__{self.sweep}__{self.label}"

    def text(self):
        text = self.deck.read_text()
        text = text.replace('"../../../meshes/', f'"{MESHES}/').replace('"../../meshes/', f'"{MESHES}/')
        lines = []
        for line in text.splitlines():
            if line.startswith("mesh "):
                for key, value in self.mesh.items():
                    line, count = re.subn(rf"\b{key}=\S+", f"{key}={value}", line)
                    if count == 0:
                        line += f" {key}={value}"
            if line.startswith("contact "):
                line = scale_number(line, "eps_n", self.eps_scale)
                line = scale_number(line, "eps_t", self.eps_t_scale)
                if self.points is not None:
                    line = re.sub(r"\bpoints=\d+", f"points={self.points}", line)
            lines.append(line)
        text = "\n".join(lines) + "\n"
        if self.steps_scale:
            text = scale_steps(text, self.steps_scale)
        for pattern, replacement in self.replace:
            text = re.sub(pattern, replacement, text, flags=re.M)
        return text


def scale_number(line, key, factor):
    if factor == 1.0:
        return line
    return re.sub(rf"\b{key}=(\S+)", lambda m: f"{key}={float(m.group(1)) * factor:.6g}", line)


def scale_steps(text, factors):
    """Multiplies the step count of phase k by factors[k] and divides its dt by the same."""
    phase = iter(factors)

    def scaled(match):
        factor = next(phase)
        steps, dt = int(match.group(1)), float(match.group(2))
        return f"steps {max(1, round(steps * factor))} dt={dt / factor:.10g}"

    return re.sub(r"steps (\d+) dt=(\S+)", scaled, text)


def element_size(variant):
    """h = c/m of meshes/indented_block.geo, the block's element length of example 6.1, or None
    for the patch tests."""
    m = variant.mesh.get("m", mesh_default(variant.deck, "m"))
    if m is not None:
        return ZONE_HALF_SIZE / float(m)
    nx = variant.mesh.get("nx", mesh_default(variant.deck, "nx"))
    return EXAMPLE_BLOCK_LENGTH / float(nx) if nx is not None else None


def mesh_default(deck, key):
    match = re.search(rf"^mesh .*\b{key}=(\S+)", Path(deck).read_text(), flags=re.M)
    return match.group(1) if match else None


def penalty_for(deck, m, alpha):
    """eps_N = alpha E / h with h = c / m: the deck's eps scaled to this mesh and alpha."""
    eps_deck = float(re.search(r"\beps_n=(\S+)", Path(deck).read_text()).group(1))
    return alpha * ELASTIC_MODULUS * m / ZONE_HALF_SIZE / eps_deck


# ---------------------------------------------------------------------------------------------
# The sweeps


# Sweep sizes keep the whole sweep near ten minutes of CPU, because the 2-core machine is shared:
# levels that would cost minutes per run (rigid sphere m = 11, elastic sphere with NTS at m >= 6,
# Cattaneo-Mindlin sphere m = 5 (3 levels only), example 6.1 at 160 x 40) are left out.


def hertz_rigid_sphere():
    deck = DECKS / "hertz_rigid_sphere.deck"
    case = "hertz_rigid_sphere"
    runs = []
    for m in (3, 4, 6, 8):
        runs.append(Variant(case, "mesh", f"m{m}", deck, {"m": m}, penalty_for(deck, m, 30), value=m))
    for alpha in (1, 3, 10, 30, 100):
        runs.append(Variant(case, "penalty", f"a{alpha}", deck, {"m": 6}, penalty_for(deck, 6, alpha),
                            value=alpha))
    for size in (8, 16, 32):
        runs.append(Variant(case, "domain", f"L{size}", deck, {"m": 6, "L": size, "H": size},
                            penalty_for(deck, 6, 30), replace=[(r"probe2_z=-32", f"probe2_z=-{size}")],
                            value=size))
    return runs


# The automatic penalty is 10 E / h (alpha = 10): issue 16 asks for results independent of the
# penalty from 1e-2 to 1e4 times it.
AUTOMATIC_PENALTY_DECADES = (0.1, 1, 10, 100, 1e3, 1e4, 1e5)


def hertz_elastic_sphere():
    deck = DECKS / "hertz_elastic_sphere.deck"
    case = "hertz_elastic_sphere"
    runs = [Variant(case, "mesh", f"m{m}", deck, {"m": m}, penalty_for(deck, m, 30), value=m)
            for m in (3, 4, 6, 8)]
    runs += [Variant(case, "penalty", f"a{alpha}", deck, {"m": 4}, penalty_for(deck, 4, alpha), value=alpha)
             for alpha in (3, 10, 30, 100)]
    nts = [(r"^contact sts (.*) points=\d+", r"contact nts \1")]
    runs += [Variant("hertz_elastic_sphere_nts", "mesh", f"m{m}", deck, {"m": m}, penalty_for(deck, m, 30),
                     replace=nts, value=m) for m in (3, 4)]
    # integration=segments (issue 16, part 1) against the Gauss points above.
    segments = [(r"^(contact sts .*points=\d+)", r"\1 integration=segments")]
    runs += [Variant("hertz_elastic_sphere_segments", "mesh", f"m{m}", deck, {"m": m},
                     penalty_for(deck, m, 30), replace=segments, value=m) for m in (3, 4, 6)]
    # surface=smooth (Nagata patches on the faceted sphere, issue 16, part 2), alone and with
    # integration=segments.
    smooth = [(r"^(contact sts .*points=\d+)", r"\1 surface=smooth")]
    runs += [Variant("hertz_elastic_sphere_smooth", "mesh", f"m{m}", deck, {"m": m},
                     penalty_for(deck, m, 30), replace=smooth, value=m) for m in (3, 4, 6)]
    smooth_segments = [(r"^(contact sts .*points=\d+)", r"\1 surface=smooth integration=segments")]
    runs += [Variant("hertz_elastic_sphere_smooth_segments", "mesh", f"m{m}", deck, {"m": m},
                     penalty_for(deck, m, 30), replace=smooth_segments, value=m) for m in (3, 4, 6)]
    # enforcement=augmented (issue 16, part 3) over the mesh levels and over six decades of the
    # penalty: the augmented results should not depend on it.
    augmented = [(r"^(contact sts .*points=\d+)", r"\1 enforcement=augmented")]
    runs += [Variant("hertz_elastic_sphere_augmented", "mesh", f"m{m}", deck, {"m": m},
                     penalty_for(deck, m, 30), replace=augmented, value=m) for m in (3, 4, 6)]
    runs += [Variant("hertz_elastic_sphere_augmented", "penalty", f"a{alpha:g}", deck, {"m": 4},
                     penalty_for(deck, 4, alpha), replace=augmented, value=alpha)
             for alpha in AUTOMATIC_PENALTY_DECADES]
    runs += [Variant(case, "penalty", f"a{alpha:g}", deck, {"m": 4}, penalty_for(deck, 4, alpha), value=alpha)
             for alpha in AUTOMATIC_PENALTY_DECADES if alpha not in (10, 100)]
    return runs


def hertz_cylinder():
    deck = DECKS / "hertz_cylinder.deck"
    case = "hertz_cylinder"
    runs = []
    for m in (4, 8, 16, 32, 64):
        h = ZONE_HALF_SIZE / m
        runs.append(Variant(case, "mesh", f"m{m}", deck, {"m": m, "thickness": h}, penalty_for(deck, m, 30),
                            replace=[(r"length=\S+", f"length={h}")], value=m))
    for alpha in (1, 3, 10, 30, 100, 300, 1000):
        runs.append(Variant(case, "penalty", f"a{alpha}", deck, {}, penalty_for(deck, 16, alpha), value=alpha))
    return runs


def cattaneo_mindlin_sphere():
    deck = DECKS / "cattaneo_mindlin_sphere.deck"
    case = "cattaneo_mindlin_sphere"
    runs = [Variant(case, "mesh", f"m{m}", deck, {"m": m}, penalty_for(deck, m, 30), value=m)
            for m in (2, 3, 4)]
    runs += [Variant(case, "steps", f"s{steps}", deck, {"m": 3}, penalty_for(deck, 3, 30),
                     steps_scale=[1, steps / 5], value=steps) for steps in (2, 5)]
    runs += [Variant(case, "penalty", f"a{alpha}", deck, {"m": 3}, penalty_for(deck, 3, alpha), value=alpha)
             for alpha in (10, 30)]
    return runs


def cattaneo_mindlin_cylinder():
    deck = DECKS / "cattaneo_mindlin_cylinder.deck"
    case = "cattaneo_mindlin_cylinder"
    runs = []
    for m in (4, 8, 16, 32):
        h = ZONE_HALF_SIZE / m
        runs.append(Variant(case, "mesh", f"m{m}", deck, {"m": m, "thickness": h}, penalty_for(deck, m, 30),
                            replace=[(r"length=\S+", f"length={h}")], value=m))
    runs += [Variant(case, "steps", f"s{steps}", deck, {}, steps_scale=[1, steps / 10], value=steps)
             for steps in (2, 5, 10, 20, 40)]
    runs += [Variant(case, "penalty", f"a{alpha}", deck, {}, penalty_for(deck, 16, alpha), value=alpha)
             for alpha in (3, 10, 30, 100, 300)]
    return runs


def patch():
    runs = []
    for kind in ("sts", "nts", "sts_matching", "sts_segments"):
        deck = DECKS / f"patch_test_{kind}.deck"
        for n in (2, 4, 8, 16):
            upper = n if kind == "sts_matching" else n + 1
            runs.append(Variant(f"patch_{kind}", "mesh", f"n{n}", deck, {"nl": n, "nu": upper, "nz": 2},
                                value=n))
        for eps in (1e3, 1e4, 1e5, 1e6, 1e7, 1e8):
            runs.append(Variant(f"patch_{kind}", "penalty", f"e{eps:g}", deck, eps_scale=eps / 1e6,
                                replace=[(r"^reference reaction:upper_top:z value=\S+",
                                          f"reference reaction:upper_top:z value={-1e-6 / (1e-3 + 1 / eps):.17g}")],
                                value=eps))
    for points in (1, 2, 3, 4):
        runs.append(Variant("patch_sts", "points", f"p{points}", DECKS / "patch_test_sts.deck",
                            points=points, value=points))
    return runs


def example_6_1():
    """Paper example 6.1(a) over mesh levels (block nx x ny, base nbx x nby), sliding-step counts
    and penalties; each sweep is compared with its finest run (accuracy_report.example_errors)."""
    case = "example_6_1"
    levels = {"10x3": (10, 3, 12, 1), "20x5": (20, 5, 24, 1), "40x10": (40, 10, 48, 2),
              "60x15": (60, 15, 72, 3), "80x20": (80, 20, 96, 4)}
    runs = []
    for label, (nx, ny, nbx, nby) in levels.items():
        runs.append(Variant(case, "mesh", label, PAPER_DECK, {"nx": nx, "ny": ny, "nbx": nbx, "nby": nby},
                            value=nx))
    for steps in (25, 50, 100, 200):
        runs.append(Variant(case, "steps", f"s{steps}", PAPER_DECK, steps_scale=[1, steps / 100], value=steps))
    for scale in (0.1, 1, 10):
        runs.append(Variant(case, "penalty", f"e{scale:g}", PAPER_DECK, eps_scale=scale, value=2.1e6 * scale))
    return runs


CASES = {
    "hertz_rigid_sphere": hertz_rigid_sphere,
    "hertz_elastic_sphere": hertz_elastic_sphere,
    "hertz_cylinder": hertz_cylinder,
    "cattaneo_mindlin_sphere": cattaneo_mindlin_sphere,
    "cattaneo_mindlin_cylinder": cattaneo_mindlin_cylinder,
    "patch": patch,
    "example_6_1": example_6_1,
}

# ---------------------------------------------------------------------------------------------
# Running and reading


def text_hash(variant):
    return hashlib.sha1(variant.text().encode()).hexdigest()


def read_results(h5_path):
    """The run's /verification errors, cost and (for example 6.1) its contact force history."""
    out = {"references": {}, "history": {}}
    with h5py.File(h5_path, "r") as f:
        summary = f["summary"].attrs
        out["outcome"] = str(summary["outcome"])
        out["iterations"] = int(summary["total_iterations"])
        out["steps"] = int(summary["steps"])
        out["cutbacks"] = int(summary["cutbacks"])
        if "verification" in f:
            for group in f["verification"].values():
                quantity = str(group.attrs["quantity"])
                out["references"][quantity] = {
                    key: float(group.attrs[key])
                    for key in ("measured", "reference", "error", "relative_error", "max_relative_error")}
        times, forces = [], []
        for step in f["steps"].values():
            if "contact" not in step:
                continue
            times.append(float(step.attrs["time"]))
            forces.append([float(v) for pair in step["contact"].values() for v in pair["total_force"][...]])
        out["history"] = {"time": times, "force": forces}
    return out


def run_variant(variant, work, binary):
    deck_dir, h5_dir = work / "decks", work / "h5"
    deck_dir.mkdir(parents=True, exist_ok=True)
    h5_dir.mkdir(parents=True, exist_ok=True)
    deck = deck_dir / f"{variant.name}.deck"
    deck.write_text(variant.text())
    h5 = h5_dir / f"{variant.name}.h5"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    process = subprocess.run(["nice", str(binary), "run", str(deck), "-o", str(h5), "--threads", "1", "-q"],
                             capture_output=True, text=True)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    result = {"case": variant.case, "sweep": variant.sweep, "label": variant.label, "value": variant.value,
              "target": variant.target,
              "h": element_size(variant),
              "wall": wall, "cpu": cpu, "exit": process.returncode}
    if h5.exists():
        try:
            result.update(read_results(h5))
        except (OSError, KeyError) as error:
            result["error"] = f"unreadable results: {error}"
    if process.returncode != 0:
        result["stderr"] = process.stderr[-2000:]
    h5.unlink(missing_ok=True)  # results are summarized in the cache; keep the disk small
    for sidecar in (h5.with_suffix(".xdmf"), h5.with_name(h5.stem + "_reactions.csv")):
        sidecar.unlink(missing_ok=True)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=str(ROOT / "build-verif"), help="build directory with src/app/covcontact")
    parser.add_argument("--binary", default=None, help="covcontact to run (default: BUILD/src/app/covcontact)")
    parser.add_argument("--work", default=None, help="directory for decks, results and the cache")
    parser.add_argument("--cases", default=",".join(CASES), help="comma-separated cases to run")
    parser.add_argument("--only", default=None, help="run only variants whose name contains this")
    parser.add_argument("--report-only", action="store_true", help="only write the report from the cache")
    parser.add_argument("--force", action="store_true", help="rerun cached runs")
    parser.add_argument("--docs", default=str(ROOT / "docs" / "verification"), help="report directory")
    args = parser.parse_args()
    binary = Path(args.binary) if args.binary else Path(args.build) / "src" / "app" / "covcontact"
    work = Path(args.work) if args.work else Path(args.build) / "accuracy"
    work.mkdir(parents=True, exist_ok=True)
    cache_path = work / "results.json"
    cache = json.loads(cache_path.read_text()) if cache_path.exists() else {}

    # The same deck reached from two sweeps (e.g. the deck's mesh level in the mesh and penalty
    # sweeps) runs once: finished runs are also found by the hash of their deck text.
    by_text = {}
    for case in CASES.values():
        for variant in case():
            if variant.name in cache:
                cache[variant.name].update(target=variant.target, h=element_size(variant))
                by_text.setdefault(text_hash(variant), cache[variant.name])

    if not args.report_only:
        for case in args.cases.split(","):
            for variant in CASES[case]():
                if variant.name in cache and not args.force or args.only and args.only not in variant.name:
                    continue
                same = by_text.get(text_hash(variant))
                if same is not None and not args.force:
                    cache[variant.name] = dict(same, case=variant.case, sweep=variant.sweep, label=variant.label,
                                               value=variant.value, target=variant.target)
                    continue
                print(f"running {variant.name} ...", flush=True)
                cache[variant.name] = run_variant(variant, work, binary)
                by_text[text_hash(variant)] = cache[variant.name]
                entry = cache[variant.name]
                print(f"  exit {entry['exit']}, {entry['cpu']:.1f} s CPU, {entry['wall']:.1f} s wall, "
                      f"{entry.get('iterations', '?')} iterations", flush=True)
                cache_path.write_text(json.dumps(cache, indent=1))
        cache_path.write_text(json.dumps(cache, indent=1))
    current = {variant.name for case in CASES.values() for variant in case()}
    accuracy_report.write({name: entry for name, entry in cache.items() if name in current}, Path(args.docs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
