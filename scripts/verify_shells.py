#!/usr/bin/python3
"""Solid-shell verification through the full program: deck templates, checks and mesh sweeps.

Every case is a deck template rendered for an element variant and a mesh level. The decks in
input/verification/shells/ are the renderings at the CTest levels (`write-decks` regenerates
them; `check` refuses a committed deck that differs from its template).

  verify_shells.py write-decks
  verify_shells.py check DECK --covcontact BIN [--scratch DIR]   (CTest: run, compare, exit 0/1)
  verify_shells.py sweep --covcontact BIN [--cases a,b]          (docs/verification/shells.md
                                                                 and shells_error_vs_time.png)
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field

import h5py
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import results_file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK_DIR = os.path.join(ROOT, "input", "verification", "shells")
DOC_DIR = os.path.join(ROOT, "docs", "verification")
MESH = "../../../meshes/"  # meshes relative to DECK_DIR

# A plain Hex8 run beside the solid-shells must show locking: an error above this.
LOCKING_ERROR = 0.5

# Small load factor for the linear benchmarks: the program is geometrically nonlinear, and at
# this factor the nonlinear response differs from the linear one by ~1e-4 relative.
LINEAR_LOAD_FACTOR = 1e-3
# At such small loads the Newton energy norm of a thin shell bottoms out between 1e-15 and
# 1e-11 of its first value (strains of ~1e-7 resolved from coordinates with eps |x| / t
# round-off), so the linear benchmarks stop at 1e-10 instead of FEAP's 1e-16: the displacement
# is then accurate to ~1e-5 in the energy norm, far below the 2% being verified. The first
# (linear) iterate of a thin structure stretches its fibres by half the squared rotation, so
# the second residual holds membrane forces up to ~(L/t)^2 times the load (7e5 for the thin
# strip): that is Newton's normal path there, not divergence, hence the raised `diverge`.
LINEAR_SOLVE = """solve
  newton energy=1e-10 diverge=1e10   # round-off floor and membrane residual of thin shells
  steps 1 dt=1
end
"""


@dataclass
class Variant:
    label: str        # solid_shell8, solid_shell18, hex8
    element: str      # deck element type
    order: int        # mesh order (2 = Hex27 -> SolidShell18)
    eas: int          # EAS parameters (ignored for hex8)
    levels: list      # mesh levels of the sweep
    ctest_level: int = 0        # 0: not a CTest deck
    tolerance: float = 0.0      # relative error accepted; 0 for a locking element (see below)

    def elements_line(self, group, material, thickness="auto"):
        if self.element == "hex8":
            return f"elements {group} hex8 material={material}"
        return f"elements {group} {self.element} material={material} thickness={thickness} eas={self.eas}"


@dataclass
class Case:
    name: str
    title: str
    render: object    # (variant, level) -> deck text
    evaluate: object  # (h5 file, variant, level) -> list of (label, value, reference)
    variants: list = field(default_factory=list)
    level_name: str = "n"


def shell_variants(levels8, levels18, ctest8, ctest18, tolerance, hex8_level=0):
    variants = [Variant("solid_shell8", "solid_shell8", 1, 3, levels8, ctest8, tolerance),
                Variant("solid_shell18", "solid_shell18", 2, 3, levels18, ctest18, tolerance)]
    if hex8_level:
        variants.append(Variant("hex8", "hex8", 1, 0, [hex8_level], hex8_level, 0.0))
    return variants


def node_weight_expression(coordinate, spacing, cells, order):
    """Consistent 1D nodal weight (trapezoidal for order 1, Simpson for order 2) of the grid node
    at `coordinate` (a muParser expression) on a uniform grid of `cells` elements."""
    if order == 1:
        i = f"rint(({coordinate})/{spacing!r})"
        return f"({spacing!r}*({i}==0 || {i}=={cells} ? 0.5 : 1))"
    step = spacing / 2
    i = f"rint(({coordinate})/{step!r})"
    odd = f"abs({i}-2*rint({i}/2))>0.5"
    return f"({step!r}/3*({i}==0 || {i}=={2 * cells} ? 1 : ({odd} ? 4 : 2)))"


# ---------------------------------------------------------------------------------------------
# Scordelis-Lo roof (MacNeal & Harder): vertical midspan displacement of the free edge 0.3024.
ROOF = dict(R=25.0, L=25.0, angle=40.0, t=0.25, E=4.32e8, weight=90.0, reference=0.3024)


def render_roof(variant, n):
    r = ROOF
    angle = math.radians(r["angle"])
    wx = node_weight_expression("x", r["L"] / n, n, variant.order)
    wt = node_weight_expression("atan(y/z)", angle / n, n, variant.order)
    load = f"-0.5*{r['weight']}*{LINEAR_LOAD_FACTOR}*{r['R']}*{wx}*{wt}*t"
    return f"""# Scordelis-Lo roof (MacNeal & Harder 1985): quarter model, {variant.label}, {n}x{n}.
# Self-weight {r['weight']} per unit area as consistent nodal loads (half on each face) times
# {LINEAR_LOAD_FACTOR} (linear regime); reference: the free edge sags 0.3024 at midspan.
title "Scordelis-Lo roof, {variant.label} {n}x{n}"
mesh "{MESH}shell_cylinder_segment.geo" R={r['R']} L={r['L']} angle={r['angle']} t={r['t']} \\
     nx={n} nt={n} order={variant.order}
material concrete svk E={r['E']} nu=0
{variant.elements_line("shell", "concrete")}
fix end0 ux            # midspan symmetry
fix end1 uy uz         # rigid diaphragm
fix side0 uy           # crown symmetry
load shell fz "{load}"
{LINEAR_SOLVE}"""


def evaluate_roof(h5, variant, n):
    sag = -mean_displacement(h5, "corner_end0_side1", 2) / LINEAR_LOAD_FACTOR
    return [("midspan free-edge sag", sag, ROOF["reference"])]


# ---------------------------------------------------------------------------------------------
# Pinched hemisphere with an 18 deg hole: radial displacement 0.0940 under the load.
def render_hemisphere(variant, n):
    return f"""# Pinched hemisphere with an 18 deg hole (MacNeal & Harder 1985): quarter model,
# {variant.label}, {n}x{n}. Unit radial loads, outward at azimuth 0 and inward at 90 deg, times
# {LINEAR_LOAD_FACTOR} (linear regime); reference: 0.0940 radial displacement under the load.
title "Pinched hemisphere, {variant.label} {n}x{n}"
mesh "{MESH}shell_sphere_segment.geo" R=10 t=0.04 polar0=18 polar1=90 azimuth=90 \\
     na={n} np={n} order={variant.order}
material steel svk E=6.825e7 nu=0.3
{variant.elements_line("shell", "steel")}
fix azimuth0 uy              # symmetry plane y = 0
fix azimuth1 ux              # symmetry plane x = 0
fix rim_azimuth0_inner uz    # rigid translation along z (one node)
load rim_azimuth0 fx "{LINEAR_LOAD_FACTOR}*t" total
load rim_azimuth1 fy "-{LINEAR_LOAD_FACTOR}*t" total
{LINEAR_SOLVE}"""


def evaluate_hemisphere(h5, variant, n):
    radial = mean_displacement(h5, "rim_azimuth0", 0) / LINEAR_LOAD_FACTOR
    return [("radial displacement under the load", radial, 0.0940)]


# ---------------------------------------------------------------------------------------------
# Pinched cylinder with rigid diaphragms: radial displacement 1.8248e-5 under the load.
def render_cylinder(variant, n):
    return f"""# Pinched cylinder with rigid end diaphragms (Belytschko et al. 1985): octant model,
# {variant.label}, {n}x{n}. A quarter of the unit pinching load at the midspan crown;
# reference: 1.8248e-5 radial displacement under the load.
title "Pinched cylinder, {variant.label} {n}x{n}"
mesh "{MESH}shell_cylinder_segment.geo" R=300 L=300 angle=90 t=3 nx={n} nt={n} \\
     order={variant.order}
material steel svk E=3e6 nu=0.3
{variant.elements_line("shell", "steel")}
fix end0 ux       # midspan symmetry
fix end1 uy uz    # rigid diaphragm
fix side0 uy      # symmetry plane y = 0
fix side1 uz      # symmetry plane z = 0
load corner_end0_side0 fz "-0.25*t" total
{LINEAR_SOLVE}"""


def evaluate_cylinder(h5, variant, n):
    radial = -mean_displacement(h5, "corner_end0_side0", 2)
    return [("radial displacement under the load", radial, 1.8248e-5)]


# ---------------------------------------------------------------------------------------------
# Thin cantilever strip, span/thickness 1000, tip force, plane strain across the width.
STRIP = dict(L=1.0, b=0.1, t=1e-3, E=1e7, nu=0.3, P=1e-6)


def strip_reference():
    s = STRIP
    D = s["E"] * s["t"] ** 3 / (12 * (1 - s["nu"] ** 2))
    G = s["E"] / (2 * (1 + s["nu"]))
    return s["P"] * s["L"] ** 3 / (3 * D * s["b"]) + s["P"] * s["L"] / (5 / 6 * G * s["b"] * s["t"])


def render_strip(variant, n):
    s = STRIP
    return f"""# Thin cantilever strip, span / thickness = 1000, {variant.label}, {n} elements along the span:
# clamped at x = 0, plane strain across the width, tip force {s['P']} (tip rotation 5e-3: linear);
# reference: plate strip (Timoshenko) tip deflection P L^3 / (3 D b) + P L / (kappa G b t).
title "Thin cantilever strip, {variant.label} {n}"
mesh "{MESH}shell_plate.geo" a={s['L']} b={s['b']} t={s['t']} nx={n} ny=1 order={variant.order}
material steel svk E={s['E']} nu={s['nu']}
{variant.elements_line("plate", "steel")}
fix plate uy      # plane strain across the width
fix xmin ux uz    # clamp
load xmax fz "{s['P']}*t" total
{LINEAR_SOLVE}"""


def evaluate_strip(h5, variant, n):
    return [("tip deflection", mean_displacement(h5, "xmax", 2), strip_reference())]


# ---------------------------------------------------------------------------------------------
# Large deflection of a cantilever under a dead tip force (Mattiasson 1981, elastica).
ELASTICA = dict(L=10.0, b=1.0, t=0.1, E=1.2e6, levels=list(range(1, 11)))  # EI = 100


def elastica_tip(k):
    """Tip displacements (u/L shortening, w/L deflection) of the inextensible elastica under a
    dead transverse tip load with P L^2 / EI = k: theta'' = -k cos(theta), theta(0) = 0,
    theta'(1) = 0, by shooting on theta'(0)."""
    def shoot(slope):
        rhs = lambda s, y: [y[1], -k * math.cos(y[0]), math.cos(y[0]), math.sin(y[0])]
        sol = solve_ivp(rhs, (0, 1), [0, slope, 0, 0], rtol=1e-12, atol=1e-12)
        return sol.y[:, -1]
    slope = brentq(lambda a: shoot(a)[1], 1e-12, k, xtol=1e-14)
    end = shoot(slope)
    return 1 - end[2], end[3]


def render_elastica(variant, n):
    e = ELASTICA
    steps = 2 * len(e["levels"])
    return f"""# Cantilever under a dead tip force up to P L^2 / EI = 10 (Mattiasson 1981): {variant.label},
# {n} elements along the span, one across the width; EI = {e['E'] * e['b'] * e['t'] ** 3 / 12:g},
# so P = t. Reference: the inextensible elastica (tip shortening and deflection at P = 1..10).
title "Cantilever elastica, {variant.label} {n}"
mesh "{MESH}shell_plate.geo" a={e['L']} b={e['b']} t={e['t']} nx={n} ny=1 order={variant.order}
material steel svk E={e['E']} nu=0
{variant.elements_line("plate", "steel")}
fix xmin all
load xmax fz "-t" total
solve
  steps {steps} dt=0.5 output_every=2
end
"""


def evaluate_elastica(h5, variant, n):
    rows = []
    L = ELASTICA["L"]
    for level in ELASTICA["levels"]:
        step = step_at_time(h5, level)
        u, w = elastica_tip(level)
        rows.append((f"P L^2/EI = {level}: tip deflection", -mean_displacement(h5, "xmax", 2, step), w * L))
        rows.append((f"P L^2/EI = {level}: tip shortening", -mean_displacement(h5, "xmax", 0, step), u * L))
    return rows


# ---------------------------------------------------------------------------------------------
# Nearly incompressible neo-Hooke block, 20% compression between rough platens.
BLOCK = dict(E=1.0, nu=0.4999, compression=0.1, reference_level=16)


def render_block(variant, n):
    return f"""# Nearly incompressible neo-Hooke block (nu = {BLOCK['nu']}) compressed by {BLOCK['compression']:.0%} between
# rough platens (bottom fixed, top moved down without sliding): {variant.label}, {n}^3 elements.
# Reference: the platen force of a fine mesh (scripts/verify_shells.py, level {BLOCK['reference_level']}).
title "Nearly incompressible block, {variant.label} {n}"
mesh "{MESH}cube.geo" n={n}
material rubber neohooke E={BLOCK['E']} nu={BLOCK['nu']}
{variant.elements_line("cube", "rubber", "z")}
fix zmin all
prescribe zmax ux 0 uy 0 uz "-{BLOCK['compression']}*t"
solve
  steps 10 dt=0.1
end
"""


# Platen force of the 16^3 SolidShell8 (eas=7) mesh at 10% compression, computed by `sweep
# --cases block --reference` (48 s). The platen edges are singular, so the force converges slowly
# (4^3: 0.14933, 8^3: 0.14227, 16^3: 0.13912; Richardson estimate of the limit 0.1366): the
# level-8 deck is held to 5% of it, which a locking element misses by orders of magnitude
# (Hex8 at 8^3: about 50 times too stiff).
BLOCK_REFERENCE_FORCE = 0.13912160


def evaluate_block(h5, variant, n):
    force = -set_reaction(h5, "zmax", 2, last_step(h5))
    return [("platen force", force, BLOCK_REFERENCE_FORCE)]


CASES = [
    Case("scordelis_lo", "Scordelis-Lo roof", render_roof, evaluate_roof,
         shell_variants([4, 8, 16, 32], [2, 4, 8, 16], 16, 8, 0.02, hex8_level=16)),
    Case("hemisphere", "Pinched hemisphere, 18 deg hole", render_hemisphere, evaluate_hemisphere,
         shell_variants([4, 8, 16, 32], [2, 4, 8, 16], 16, 8, 0.02)),
    Case("pinched_cylinder", "Pinched cylinder with diaphragms", render_cylinder,
         evaluate_cylinder, shell_variants([8, 16, 32, 64], [4, 8, 16, 32], 32, 16, 0.02)),
    Case("thin_strip", "Thin cantilever strip L/t = 1000, tip force", render_strip,
         evaluate_strip, shell_variants([8, 16, 32, 64], [4, 8, 16, 32], 32, 32, 0.01,
                                        hex8_level=32)),
    Case("elastica", "Cantilever elastica, P L^2/EI = 1..10", render_elastica, evaluate_elastica,
         shell_variants([8, 16, 32, 64], [4, 8, 16, 32], 32, 16, 0.02)),
    Case("block", "Nearly incompressible neo-Hooke block", render_block, evaluate_block,
         [Variant("solid_shell8", "solid_shell8", 1, 7, [4, 8], 8, 0.05),
          Variant("hex8", "hex8", 1, 0, [4, 8], 8, 0.0)]),
]


# ---------------------------------------------------------------------------------------------
def mean_displacement(h5, node_set, component, step=None):
    nodes = h5[f"mesh/node_sets/{node_set}/nodes"][:]
    step = step or last_step(h5)
    return float(h5[f"steps/{step}/displacement"][:][nodes, component].mean())


def set_reaction(h5, node_set, component, step):
    return float(results_file.set_reaction(h5[f"steps/{step}"], node_set)[component])


def last_step(h5):
    return sorted(h5["steps"].keys())[-1]


def step_at_time(h5, target):
    for name in h5["steps"]:
        if abs(h5[f"steps/{name}"].attrs["time"] - target) < 1e-9:
            return name
    raise KeyError(f"no output step at time {target}")


def deck_name(case, variant):
    return f"{case.name}_{variant.label}.deck"


def run_deck(covcontact, deck_path, scratch):
    os.makedirs(scratch, exist_ok=True)
    results = os.path.join(scratch, os.path.basename(deck_path).replace(".deck", ".h5"))
    start = time.monotonic()
    process = subprocess.run([covcontact, "run", deck_path, "-o", results, "-q"],
                             capture_output=True, text=True)
    seconds = time.monotonic() - start
    if process.returncode != 0:
        raise RuntimeError(f"{deck_path}: covcontact exited with {process.returncode}\n"
                           f"{process.stdout}{process.stderr}")
    return results, seconds


def relative_error(value, reference):
    return abs(value - reference) / abs(reference)


def command_write_decks(_args):
    os.makedirs(DECK_DIR, exist_ok=True)
    for case in CASES:
        for variant in case.variants:
            if variant.ctest_level:
                path = os.path.join(DECK_DIR, deck_name(case, variant))
                with open(path, "w") as deck:
                    deck.write(case.render(variant, variant.ctest_level))
                print("wrote", os.path.relpath(path, ROOT))


def command_check(args):
    stem = os.path.basename(args.deck)
    for case in CASES:
        for variant in case.variants:
            if variant.ctest_level and deck_name(case, variant) == stem:
                return check_case(args, case, variant)
    print(f"{stem}: not a deck of scripts/verify_shells.py")
    return 1


def check_case(args, case, variant):
    with open(args.deck) as deck:
        if deck.read() != case.render(variant, variant.ctest_level):
            print(f"{args.deck} differs from its template; run verify_shells.py write-decks")
            return 1
    scratch = args.scratch or tempfile.mkdtemp(prefix="verify_shells_")
    results, seconds = run_deck(args.covcontact, args.deck, scratch)
    failed = False
    with h5py.File(results, "r") as h5:
        for label, value, reference in case.evaluate(h5, variant, variant.ctest_level):
            error = relative_error(value, reference)
            if variant.tolerance:
                passed = error <= variant.tolerance
                expectation = f"tolerance {variant.tolerance:.0%}"
            else:
                passed = error >= LOCKING_ERROR
                expectation = f"locking: error above {LOCKING_ERROR:.0%}"
            failed = failed or not passed
            print(f"{case.name} {variant.label}: {label} = {value:.6g}, reference {reference:.6g}, "
                  f"error {error:.3%} ({expectation}) {'ok' if passed else 'FAILED'}")
    print(f"run time {seconds:.2f} s")
    return 1 if failed else 0


def render_for_scratch(case, variant, level, scratch):
    """A sweep deck lives in the scratch directory, so its mesh path becomes absolute."""
    text = case.render(variant, level).replace(f'"{MESH}', f'"{os.path.join(ROOT, "meshes")}/')
    path = os.path.join(scratch, f"{case.name}_{variant.label}_{level}.deck")
    with open(path, "w") as deck:
        deck.write(text)
    return path


def sweep_case(args, case, scratch):
    rows = []
    for variant in case.variants:
        for level in variant.levels:
            deck = render_for_scratch(case, variant, level, scratch)
            try:
                results, seconds = run_deck(args.covcontact, deck, scratch)
            except RuntimeError as failure:
                print(failure)
                rows.append((variant, level, "run failed", math.nan, math.nan, math.nan, math.nan))
                continue
            with h5py.File(results, "r") as h5:
                evaluations = case.evaluate(h5, variant, level)
            worst = max(evaluations, key=lambda e: relative_error(e[1], e[2]))
            error = relative_error(worst[1], worst[2])
            rows.append((variant, level, worst[0], worst[1], worst[2], error, seconds))
            print(f"{case.name} {variant.label} {case.level_name}={level}: {worst[0]} "
                  f"{worst[1]:.6g} (ref {worst[2]:.6g}) error {error:.3%} in {seconds:.2f} s",
                  flush=True)
    return rows


def block_reference(args, scratch):
    """Platen force of the fine SolidShell8 mesh that the block case is compared against."""
    variant = CASES[-1].variants[0]
    deck = render_for_scratch(CASES[-1], variant, BLOCK["reference_level"], scratch)
    results, seconds = run_deck(args.covcontact, deck, scratch)
    with h5py.File(results, "r") as h5:
        force = -set_reaction(h5, "zmax", 2, last_step(h5))
    print(f"block reference (level {BLOCK['reference_level']}): {force:.8g} in {seconds:.1f} s")
    return force


def write_report(all_rows):
    os.makedirs(DOC_DIR, exist_ok=True)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(figsize=(6.4, 4.4))
    lines = ["| case | element | mesh | quantity (worst) | value | reference | error | run time [s] |",
             "|---|---|---|---|---|---|---|---|"]
    for case, rows in all_rows:
        by_variant = {}
        for variant, level, label, value, reference, error, seconds in rows:
            lines.append(f"| {case.title} | {variant.label} | {level} | {label} | {value:.5g} | "
                         f"{reference:.5g} | {error:.2%} | {seconds:.2f} |")
            if variant.tolerance and math.isfinite(error):
                by_variant.setdefault(variant.label, []).append((seconds, max(error, 1e-6)))
        color = f"C{[c.name for c in CASES].index(case.name)}"  # one colour per case
        for label, points in by_variant.items():
            times, errors = zip(*points)
            quadratic = label.endswith("18")
            axes.loglog(times, errors, color=color, marker="s" if quadratic else "o",
                        linestyle="--" if quadratic else "-", label=f"{case.name} {label}")
    axes.axhline(0.02, color="grey", linestyle=":", linewidth=1)
    axes.set_xlabel("run time of covcontact [s]")
    axes.set_ylabel("relative error (worst quantity)")
    axes.legend(fontsize=6, ncol=2)
    axes.grid(True, which="both", linewidth=0.3)
    figure.tight_layout()
    figure.savefig(os.path.join(DOC_DIR, "shells_error_vs_time.png"), dpi=110)
    replace_between_markers(os.path.join(DOC_DIR, "shells.md"), "\n".join(lines))
    print("\n".join(lines))


def replace_between_markers(path, table):
    """Puts the sweep table into the verification page between its sweep-table markers."""
    begin, end = "<!-- sweep-table:begin -->", "<!-- sweep-table:end -->"
    with open(path) as page:
        text = page.read()
    if begin not in text or end not in text:
        raise RuntimeError(f"{path} has no {begin} ... {end} section")
    head, rest = text.split(begin, 1)
    tail = rest.split(end, 1)[1]
    with open(path, "w") as page:
        page.write(f"{head}{begin}\n{table}\n{end}{tail}")


def command_sweep(args):
    global BLOCK_REFERENCE_FORCE
    scratch = args.scratch or tempfile.mkdtemp(prefix="verify_shells_")
    os.makedirs(scratch, exist_ok=True)
    wanted = set(args.cases.split(",")) if args.cases else {case.name for case in CASES}
    if "block" in wanted and args.reference:
        BLOCK_REFERENCE_FORCE = block_reference(args, scratch)
    all_rows = [(case, sweep_case(args, case, scratch)) for case in CASES if case.name in wanted]
    write_report(all_rows)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)
    commands.add_parser("write-decks", help="render the CTest decks into input/verification/shells")
    check = commands.add_parser("check", help="run one committed deck and compare (CTest)")
    check.add_argument("deck")
    check.add_argument("--covcontact", required=True)
    check.add_argument("--scratch")
    sweep = commands.add_parser("sweep", help="all mesh levels, markdown table and PNG")
    sweep.add_argument("--covcontact", required=True)
    sweep.add_argument("--cases", help="comma-separated case names (default: all)")
    sweep.add_argument("--scratch")
    sweep.add_argument("--reference", action="store_true",
                       help="recompute the block's fine-mesh reference force first")
    args = parser.parse_args()
    handler = {"write-decks": command_write_decks, "check": command_check,
               "sweep": command_sweep}[args.command]
    return handler(args)


if __name__ == "__main__":
    sys.exit(main())
