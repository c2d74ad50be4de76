#!/usr/bin/python3
"""The issue's "other code" column, reproduced (issue 14): an STS or NTS ironing deck of
input/stress/ironing/ written as a CalculiX 2.20 deck on the same gmsh mesh (the deck's mesh
line: geometry and parameters), with C3D8 (the fully integrated trilinear hexahedron, as our
Hex8), the decoupled neo-Hooke law W = C10 (I1bar - 3) + (J - 1)^2 / D1 from the deck's E and nu,
face-to-face penalty contact with the deck's eps_n, eps_t and mu (slab_top the slave, the die's
cylindrical face the master), and 20 press and 80 slide increments of fixed size. It prints
Newton iterations per increment in developed sliding (t in (0.4, 1], as
docs/verification/sliding.md counts ours), cut-backs, the die's mean force, its jitter and the
CPU time. With --ours the CovContact deck runs right after it, one thread each, with both
materials `neohooke_decoupled` and `predictor=extrapolate` (the report's column), for a CPU
time ratio under the same load. One command from a built checkout (about 3 + 2 minutes on the
deck's mesh):

    /usr/bin/python3 scripts/ironing_calculix.py [--case ironing_sts_mu03_wide]
        [--ours | --ours-only] [--cutbacks] [--mesh nx=36 ny=16 ...] [--work DIR]
        [--limit SECONDS]

--mesh overrides mesh-line parameters for both programs (a refined mesh); --cutbacks lets
CalculiX cut an increment back (its automatic incrementation, down to 1e-4 of the increment)
instead of stopping at the first that diverges. CalculiX's contact is face-to-face whatever the
deck's kind. Nothing is written into the source tree.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import bench_calculix  # noqa: E402
import bench_runs  # noqa: E402
import ironing_force_level  # noqa: E402
import ironing_predictor  # noqa: E402
import ironing_summary  # noqa: E402

# No memory limit of our own: the machine's 24 GiB.
MEMORY_LIMIT = 1 << 40

# The loading every ironing deck gives the die, which the CalculiX deck repeats (MODEL below).
DIE_LOADING = 'prescribe die_top ux "4*max(t-0.2,0)/0.8" uy 0 uz "-1.4*min(t/0.2,1)"'


def decoupled_constants(young, poisson):
    """C10 = mu/2 and D1 = 2/K from the small-strain constants, as
    src/materials/neo_hooke_decoupled.cpp takes them."""
    shear = young / (2 * (1 + poisson))
    bulk = young / (3 * (1 - 2 * poisson))
    return shear / 2, 2 / bulk


def deck_model(case, overrides):
    """What the CalculiX deck takes from the CovContact deck `case`: the geometry file and its
    parameters (with `overrides`), the materials {body: (E, nu)}, and eps_n, eps_t, mu."""
    text = ironing_force_level.deck_text(case, "neohooke")
    mesh = re.search(r'^mesh "([^"]+)"(.*)$', text, flags=re.M)
    parameters = dict(item.split("=", 1) for item in mesh.group(2).split())
    parameters.update(dict(item.split("=", 1) for item in overrides))
    laws = {name: (float(e), float(nu)) for name, e, nu in re.findall(
        r"^material (\w+) neohooke E=(\S+) nu=(\S+)$", text, flags=re.M)}
    bodies = dict(re.findall(r"^elements (\w+) hex8 material=(\w+)$", text, flags=re.M))
    contact = re.search(r"^contact (\w+) (.*)$", text, flags=re.M)
    options = dict(item.split("=", 1) for item in contact.group(2).split() if "=" in item)
    if contact.group(1) not in ("sts", "nts") or "eps_n" not in options:
        sys.exit(f"{case}: CalculiX needs a meshed die (sts or nts) with eps_n and eps_t given")
    if options.get("slave") != "slab_top" or options.get("master") != "die_bottom":
        sys.exit(f"{case}: expected slave=slab_top master=die_bottom, as the CalculiX deck has")
    if DIE_LOADING not in text or "fix slab_bottom all" not in text:
        sys.exit(f"{case}: expected '{DIE_LOADING}' and 'fix slab_bottom all', which the "
                 "CalculiX deck repeats")
    return {"geo": mesh.group(1), "parameters": parameters,
            "materials": {body: laws[law] for body, law in bodies.items()},
            "eps_n": float(options["eps_n"]),
            "eps_t": float(options.get("eps_t", options["eps_n"])),
            "mu": float(options.get("mu", 0))}


def write_inp(msh, path, model, press_increments, slide_increments, cutbacks):
    with open(path, "w") as out:
        out.write("** Ironing (issue 14) for CalculiX 2.20, by scripts/ironing_calculix.py\n")
        bench_calculix.write_mesh(out, msh, "C3D8", ("slab_bottom", "die_top"),
                                  ("slab_top", "die_bottom"))
        for name, (young, poisson) in model["materials"].items():
            c10, d1 = decoupled_constants(young, poisson)
            out.write(f"*MATERIAL, NAME=M_{name}\n*HYPERELASTIC, NEO HOOKE\n{c10:.12g}, {d1:.12g}\n"
                      f"*SOLID SECTION, ELSET={name}, MATERIAL=M_{name}\n")
        friction = f"*FRICTION\n{model['mu']:g}, {model['eps_t']:g}\n" if model["mu"] > 0 else ""
        out.write(MODEL.format(eps_n=model["eps_n"], friction=friction,
                               static_press=static(1.0 / press_increments, cutbacks),
                               static_slide=static(1.0 / slide_increments, cutbacks)))


def static(increment, cutbacks):
    """*STATIC at a fixed increment; with `cutbacks`, CalculiX may cut it back (down to 1e-4 of
    it) after a failed increment and grow it again up to the fixed size."""
    if not cutbacks:
        return f"*STATIC, DIRECT\n{increment:.12g}, 1."
    return f"*STATIC\n{increment:.12g}, 1., {increment * 1e-4:.12g}, {increment:.12g}"


# The press (die_top down 1.4) and the slide (4 along x) as two steps of 20 and 80 increments, as
# the CovContact decks' equal steps; *STATIC, DIRECT keeps the increment fixed, so that a
# diverging increment ends the run (--cutbacks: CalculiX's automatic incrementation).
MODEL = """\
*SURFACE INTERACTION, NAME=INTERFACE
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR
{eps_n:g}
{friction}*CONTACT PAIR, INTERACTION=INTERFACE, TYPE=SURFACE TO SURFACE
slab_top, die_bottom
*BOUNDARY
slab_bottom, 1, 3, 0.
*STEP, NLGEOM, INC=100000
{static_press}
*BOUNDARY
die_top, 1, 2, 0.
die_top, 3, 3, -1.4
*NODE PRINT, NSET=die_top, TOTALS=ONLY
RF
*END STEP
*STEP, NLGEOM, INC=100000
{static_slide}
*BOUNDARY
die_top, 1, 1, 4.
die_top, 2, 2, 0.
die_top, 3, 3, -1.4
*NODE PRINT, NSET=die_top, TOTALS=ONLY
RF
*END STEP
"""

# STEP INC ATT ITRS TOT.TIME STEP.TIME INC.TIME; a failed attempt has a U after its number.
STA_ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)(U?)\s+(\d+)\s+[-+.\dEe]+\s+([-+.\dEe]+)")


def read_increments(sta):
    """[(step, iterations, step time, failed)] of every attempt in CalculiX's .sta file."""
    rows = []
    with open(sta) as stream:
        for line in stream:
            match = STA_ROW.match(line)
            if match:
                rows.append((int(match.group(1)), int(match.group(5)), float(match.group(6)),
                             match.group(4) == "U"))
    return rows


def run(command, work, limit):
    """Runs `command` on one thread (bench_runs.measure: CPU time and exit from the kernel)."""
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    measured = bench_runs.measure(command, work, env, limit, MEMORY_LIMIT)
    return {"exit": measured["stopped"] or measured["exit_code"], "cpu": measured["cpu"],
            "wall": measured["wall"]}


def run_calculix(args, model, work):
    msh = os.path.join(work, "mesh.msh")
    bench_calculix.mesh_geo(model["geo"], model["parameters"], msh)
    write_inp(msh, os.path.join(work, "job.inp"), model, 20, 80, args.cutbacks)
    result = run(["ccx", "-i", "job"], work, args.limit)
    attempts = read_increments(os.path.join(work, "job.sta"))
    # Run time: the press step's time t_s in [0, 1] is t = 0.2 t_s, the slide's 0.2 + 0.8 t_s.
    its_at = {round(0.2 * t if step == 1 else 0.2 + 0.8 * t, 9): n
              for step, n, t, failed in attempts if not failed}
    # The .dat file has the converged increments' totals, at total times: press [0, 1], slide
    # (1, 2].
    curve = [(round(0.2 * t if t <= 1 + 1e-9 else 0.2 + 0.8 * (t - 1), 9), fx, fz)
             for t, fx, _, fz in
             bench_calculix.read_reaction_totals(os.path.join(work, "job.dat"))]
    times = [t for t, _, _ in curve]
    if sorted(times) != sorted(its_at):
        sys.exit(f"{work}: the .sta and .dat files do not list the same increments")
    fz = [-z for _, _, z in curve]  # the reaction on die_top: the press pushes down (+z)
    fx = [-x for _, x, _ in curve]
    result.update({"steps": len(curve), "final_t": times[-1] if times else 0.0,
                   "iterations": sum(its_at.values()),
                   "discarded_iterations": sum(row[1] for row in attempts if row[3]),
                   "cutbacks": sum(1 for row in attempts if row[3]),
                   "press_Fz": next((z for t, z in zip(times, fz) if abs(t - 0.2) < 1e-9),
                                    float("nan"))})
    result.update(ironing_summary.sliding_metrics(times, [its_at[t] for t in times], fx, fz))
    return result


def run_ours(args, model, work):
    """The deck with both materials decoupled, `predictor=extrapolate` and the mesh line of
    `model` (the --mesh overrides applied)."""
    text = ironing_predictor.with_predictor(
        ironing_force_level.deck_text(args.case, "neohooke_decoupled"))
    mesh_line = f'mesh "{model["geo"]}" ' + " ".join(
        f"{k}={v}" for k, v in model["parameters"].items())
    text = re.sub(r'^mesh "[^"]+".*$', lambda _: mesh_line, text, count=1, flags=re.M)
    deck = os.path.join(work, "ours.deck")
    open(deck, "w").write(text)
    stem = os.path.join(work, "ours")
    result = run([args.covcontact, "run", deck, "-o", stem + ".h5", "--threads", "1"], work,
                 args.limit)
    result.update(ironing_summary.summarize(stem + ".h5"))
    result["press_Fz"] = ironing_force_level.press_force(stem)
    return result


def report(program, result):
    """One line per run; nan where the run stopped before developed sliding."""
    values = {key: float("nan") for key in ("its_developed", "Fz_mean", "Fx/Fz_mean",
                                            "jitter_Fz_%", "jitter_Fx/Fz_%")}
    values.update(result)
    print(f"{program}: exit {{exit}}, {{steps}} steps to t = {{final_t:.3f}}, {{iterations}} "
          "iterations (+{discarded_iterations} in failed attempts), {cutbacks} cut-backs, "
          "developed {its_developed:.2f} per step, Fz at t = 0.2 {press_Fz:.3f}, mean Fz "
          "{Fz_mean:.3f}, Fx/Fz {Fx/Fz_mean:.3f}, jitter Fz {jitter_Fz_%:.2f} % Fx/Fz "
          "{jitter_Fx/Fz_%:.2f} %, CPU {cpu:.1f} s, wall {wall:.1f} s".format(**values),
          flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", default="ironing_sts_mu03_wide",
                        help="a deck of input/stress/ironing/ (without .deck)")
    parser.add_argument("--mesh", nargs="*", default=[], help="mesh-line parameters, k=v")
    parser.add_argument("--cutbacks", action="store_true",
                        help="let CalculiX cut an increment back (default: fixed increments)")
    parser.add_argument("--ours", action="store_true", help="run the CovContact deck after it")
    parser.add_argument("--ours-only", action="store_true", help="run only the CovContact deck")
    parser.add_argument("--covcontact", default=os.path.join(ROOT, "build", "src", "app",
                                                             "covcontact"))
    parser.add_argument("--work", default="/tmp/ironing_calculix")
    parser.add_argument("--limit", type=float, default=3600, help="seconds per run")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print(f"load before: {os.getloadavg()[0]:.2f}", flush=True)
    model = deck_model(args.case, args.mesh)
    calculix = None
    if not args.ours_only:
        calculix = run_calculix(args, model, args.work)
        report("CalculiX 2.20", calculix)
    if args.ours or args.ours_only:
        ours = run_ours(args, model, args.work)
        report("CovContact", ours)
        if calculix:
            print(f"CPU time ratio CalculiX / CovContact: {calculix['cpu'] / ours['cpu']:.2f}")

if __name__ == "__main__":
    main()
