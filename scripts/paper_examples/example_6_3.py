"""Paper example 6.3: a semi-cylinder on a rigid parabolic cylinder, STAS (Table 5, Fig. 14).

Runs the four Table 5 decks (press + 20 spiral steps with tangent no_curvature, main, full,
exact) and the 1000-step spiral deck, then writes into docs/paper/: example_6_3_table5.md,
the figures example_6_3_trajectory.png, example_6_3_iterations.png, example_6_3_force_ratio.png
and the page example_6_3.md.
"""
import h5py
import matplotlib
import matplotlib.ticker
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .common import convergence_table, markdown_table  # noqa: E402

DECKS = {"no_curvature": "semi_cylinder_6_3_no_curvature.deck",
         "main": "semi_cylinder_6_3_main.deck",
         "full": "semi_cylinder_6_3_full.deck",
         "exact": "semi_cylinder_6_3_exact.deck"}
SPIRAL_DECK = "semi_cylinder_6_3_spiral.deck"
TABLE_STEPS = 20            # Table 5: the first 20 load steps of the spiral
PRESS_STEPS = 1             # the press is step 1 of every deck
ENERGY_TOLERANCE = 1e-16    # FEAP's default, relative energy norm
RESIDUAL_TOLERANCE = 1e-10  # relative residual norm
# Table 5 of the paper, iterations per load step: case 1 without curvature parts, case 2 main
# part only.
PAPER_NO_CURVATURE = [9, 8, 5] + [4] * 17
PAPER_MAIN = [10] + [13] * 17 + [12, 11]
# Rigid surface z = c x^2, body's axis at height R above the vertex at the start.
PARABOLA_C = 0.05
RADIUS = 1.0
FRICTION = 0.3
FOOT_POINT_ITERATIONS = 50  # fixed-point iterations for the foot point (converges in ~10)


def iterations_to(results, column, tolerance):
    """Per step: first iteration of the converged attempt with column <= tolerance."""
    table = convergence_table(results)
    counts = []
    for step in np.unique(table["step"]):
        rows = table[table["step"] == step]
        rows = rows[rows["attempt"] == rows["attempt"].max()]
        met = rows["iteration"][rows[column] <= tolerance]
        counts.append(int(met.min()) if met.size else None)
    return counts


def cumulative_cells(counts):
    cells, total = [], 0
    for count in counts:
        total += count
        cells.append(f"{count} ({total})")
    return cells


def table5(counts_by_tangent, criterion):
    header = ["spiral step", "paper case 1 (no curvature)", "no_curvature", "paper case 2 (main)",
              "main", "full", "exact"]
    rows = []
    paper1 = cumulative_cells(PAPER_NO_CURVATURE)
    paper2 = cumulative_cells(PAPER_MAIN)
    ours = {name: cumulative_cells(c[PRESS_STEPS:PRESS_STEPS + TABLE_STEPS])
            for name, c in counts_by_tangent.items()}
    for k in range(TABLE_STEPS):
        rows.append([k + 1, paper1[k], ours["no_curvature"][k], paper2[k], ours["main"][k],
                     ours["full"][k], ours["exact"][k]])
    press = ["press"] + ["-", counts_by_tangent["no_curvature"][0], "-",
                         counts_by_tangent["main"][0], counts_by_tangent["full"][0],
                         counts_by_tangent["exact"][0]]
    return (f"Iterations per load step (cumulative) until {criterion}.\n\n"
            + markdown_table(header, [press] + rows))


def spiral_history(results):
    """Per written step: time, iterations, axis position, contact total force and its
    tangential part (the sum of the points' tangential tractions times their weights)."""
    with h5py.File(results, "r") as f:
        loaded = f["mesh/node_sets/top_edges/nodes"][...]
        names = sorted(f["steps"])
        steps = [f["steps"][n] for n in names]
        time = np.array([s.attrs["time"] for s in steps])
        iterations = np.array([s.attrs["iterations"] for s in steps])
        axis = np.array([s["displacement"][...][loaded].mean(axis=0) for s in steps])
        pairs = [s["contact/trough"] for s in steps]
        force = np.array([p["total_force"][...] for p in pairs])
        tangential = np.array([(p["tangential_traction"][...] * p["weight"][...][:, None]).sum(0)
                               for p in pairs])
        summary = dict(f["summary"].attrs)
    axis[:, 2] += RADIUS  # the axis starts at (0, 0, R)
    return dict(time=time, iterations=iterations, axis=axis, force=force, tangential=tangential,
                summary=summary)


def rigid_normal_below(axis):
    """Normal of z = c x^2 at the foot point a of the equidistant motion under the axis
    (axis_x = a - 2 c a d / q, q = sqrt(1 + 4 c^2 a^2), d its distance: fixed-point iteration)."""
    a = axis[0]
    for _ in range(FOOT_POINT_ITERATIONS):
        q = np.sqrt(1 + 4 * PARABOLA_C**2 * a * a)
        distance = (axis[2] - PARABOLA_C * a * a) * q
        a = axis[0] + 2 * PARABOLA_C * a * distance / q
    normal = np.array([-2 * PARABOLA_C * a, 0.0, 1.0])
    return normal / np.linalg.norm(normal)


def force_ratios(history):
    """|F_t| / |F_n| of the total contact force, split (1) into the sum of the points' tangential
    tractions and the rest (the normal tractions along the master facets' normals: what
    Coulomb's law bounds) and (2) along the rigid surface's normal under the axis."""
    own, rigid = [], []
    for axis, force, tangential in zip(history["axis"], history["force"], history["tangential"]):
        normal_part = np.linalg.norm(force - tangential)
        own.append(np.linalg.norm(tangential) / normal_part if normal_part else np.nan)
        nu = rigid_normal_below(axis)
        along = force @ nu
        rigid.append(np.linalg.norm(force - along * nu) / abs(along) if along else np.nan)
    return np.array(own), np.array(rigid)


def plot_trajectory(history, path):
    axis = history["axis"]
    figure, (top, side) = plt.subplots(1, 2, figsize=(10, 4.2))
    top.plot(axis[:, 0], axis[:, 1], "-", color="tab:blue")
    top.set_xlabel("x of the axis"), top.set_ylabel("y of the axis")
    top.set_title("Path of the semi-cylinder's axis (plan view)")
    top.grid(True, alpha=0.3)
    x = np.linspace(-1.5, axis[:, 0].max() + 1.5, 300)
    side.plot(x, PARABOLA_C * x * x, "k-", label="rigid surface z = 0.05 x²")
    side.plot(axis[:, 0], axis[:, 2], "-", color="tab:blue", label="axis")
    for k in np.linspace(0, len(axis) - 1, 6).astype(int):
        angle = np.linspace(np.pi, 2 * np.pi, 60)
        side.plot(axis[k, 0] + RADIUS * np.cos(angle), axis[k, 2] + RADIUS * np.sin(angle),
                  color="tab:orange", lw=0.8)
    side.set_aspect("equal"), side.grid(True, alpha=0.3)
    side.set_xlabel("x"), side.set_ylabel("z"), side.legend(loc="upper left")
    side.set_title("Side view (x-z): axis and outer radius")
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def plot_iterations(history, path):
    figure, ax = plt.subplots(figsize=(8, 3.5))
    step = np.arange(len(history["iterations"])) - PRESS_STEPS + 1
    ax.plot(step, history["iterations"], ".", ms=3)
    ax.set_xlabel("spiral step (0 = press)")
    ax.set_ylabel("Newton iterations\n(energy 1e-16 and residual 1e-10)")
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))
    ax.set_title("Example 6.3: iterations per step, tangent without curvature parts")
    ax.grid(True, alpha=0.3)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def plot_force_ratio(own, rigid, path):
    figure, ax = plt.subplots(figsize=(8, 3.5))
    step = np.arange(len(own)) - PRESS_STEPS + 1
    ax.plot(step, rigid, "-", lw=1, color="tab:orange",
            label="against the rigid surface's normal below the axis")
    ax.plot(step, own, "-", lw=1.5, color="tab:blue",
            label="against the contact points' own (facet) normals")
    ax.axhline(FRICTION, color="k", ls="--", lw=0.8, label="mu = 0.3")
    ax.set_xlabel("spiral step (0 = press)"), ax.set_ylabel("|F_t| / |F_n|")
    ax.set_title("Total contact force: tangential over normal part")
    ax.set_ylim(0, 0.45), ax.grid(True, alpha=0.3), ax.legend(loc="lower right", fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def reproduce(context):
    decks = context.repo / "input" / "paper"
    energy, residual = {}, {}
    for tangent, deck in DECKS.items():
        results = context.run(decks / deck, deck.removesuffix(".deck"))
        energy[tangent] = iterations_to(results, "relative_energy", ENERGY_TOLERANCE)
        residual[tangent] = iterations_to(results, "relative_residual", RESIDUAL_TOLERANCE)
    spiral = context.run(decks / SPIRAL_DECK, SPIRAL_DECK.removesuffix(".deck"))
    history = spiral_history(spiral)
    own, rigid = force_ratios(history)
    plot_trajectory(history, context.docs / "example_6_3_trajectory.png")
    plot_iterations(history, context.docs / "example_6_3_iterations.png")
    plot_force_ratio(own, rigid, context.docs / "example_6_3_force_ratio.png")
    tables = (table5(energy, f"relative energy <= {ENERGY_TOLERANCE:g} (FEAP's default)")
              + "\n" + table5(residual, f"relative residual <= {RESIDUAL_TOLERANCE:g}"))
    (context.docs / "example_6_3_table5.md").write_text(tables)
    table_window = slice(PRESS_STEPS, PRESS_STEPS + TABLE_STEPS)
    sliding = slice(PRESS_STEPS, None)
    spiral_steps = history["iterations"][sliding]
    facts = dict(
        energy={name: sum(c[table_window]) for name, c in energy.items()},
        residual={name: sum(c[table_window]) for name, c in residual.items()},
        press={name: c[0] for name, c in energy.items()},
        outcome=history["summary"]["outcome"], steps=len(spiral_steps),
        cutbacks=int(history["summary"]["cutbacks"]), iterations=int(spiral_steps.sum()),
        histogram={int(k): int(n) for k, n in enumerate(np.bincount(spiral_steps)) if n},
        own=(float(np.nanmin(own[sliding])), float(np.nanmax(own[sliding]))),
        rigid=(float(np.nanmin(rigid[sliding])), float(np.nanmax(rigid[sliding]))),
        normal=(float(np.linalg.norm(history["force"][PRESS_STEPS] - history["tangential"][PRESS_STEPS])),
                float(np.linalg.norm(history["force"][-1] - history["tangential"][-1]))),
        final_axis=history["axis"][-1],
        wall={name: seconds for name, seconds in context.wall_seconds.items()
              if name.startswith("semi_cylinder_6_3")})
    (context.docs / "example_6_3.md").write_text(page(facts, tables))
    print(f"   6.3: Table 5 cumulative (energy): {facts['energy']}; spiral: {facts['outcome']}, "
          f"{facts['steps']} steps, {facts['cutbacks']} cut-backs, "
          f"{facts['iterations']} iterations", flush=True)


def page(facts, tables):
    """docs/paper/example_6_3.md: setup, Table 5, figures and every difference from the paper."""
    energy, residual = facts["energy"], facts["residual"]
    histogram = ", ".join(f"{n} step{'s' if n != 1 else ''} with {k}"
                          for k, n in facts["histogram"].items())
    wall = markdown_table(["run", "wall time [s]"],
                          [[name, f"{seconds:.1f}"]
                           for name, seconds in sorted(facts["wall"].items())])
    x, y, z = facts["final_axis"]
    return f"""# Example 6.3: a semi-cylinder sliding on a rigid parabolic cylinder (STAS)

Paper: section 6.3, eqs. (117)-(127), Fig. 14, Table 5. Decks:
`input/paper/semi_cylinder_6_3_*.deck` (shared model `semi_cylinder_6_3_model.inc`, mesh
`meshes/semi_cylinder.geo`). Produced by `scripts/reproduce_paper.py --only 6.3`.

## Model and the choices the paper leaves open

- Semi-circular cylindrical **shell**, outer (contact) radius R = 1, length l = 0.4, thickness
  t = 0.1 (R/10, our choice), 16 linear solid-shells around the half circumference x 3 along l
  ("16 x 3"), one layer through the thickness, E = 2.1e4, nu = 0.3 (St. Venant-Kirchhoff).
- Rigid parabolic cylinder z = 0.05 x^2, axis along y; STAS with 4 x 4 Gauss points per master
  segment (the shell's outer faces), mu = 0.3, eps_N = eps_T = 2.1e5 (= 10 E/R; the paper gives
  no penalty for 6.3).
- The semi-cylinder moves, as in the paper: its two straight edges (at the height of the axis)
  get the whole displacement, a translation without rotation. Press dz = -0.01 in one step, then
  1000 steps of the spiral with v = 1e-2, H = 20, T = 1000, as "an equidistant motion of the
  central axis with the distance R + dz = 0.99" (the paper's words): we prescribe the exact
  offset curve at distance 0.99 (see difference 6).
- Convergence: Newton until both the relative energy norm <= 1e-16 (FEAP's default) and the
  relative residual <= 1e-10; the tables count, per step, the first iteration at which each
  criterion alone holds (same run).

## Table 5: first 20 spiral steps

The paper's case 1 is "without curvature parts", case 2 "main part only". Cells: iterations of
the step (cumulative). The press is listed separately (the paper does not say whether its load
step 1 is the press; its l.s. 1 with 9 iterations would fit either).

{tables}
Cumulative over the 20 spiral steps (energy criterion): without curvature parts
**{energy['no_curvature']}** (paper 90), main part only **{energy['main']}** (paper 254), full
{energy['full']}, exact {energy['exact']}. At relative residual <= 1e-10: without curvature
{residual['no_curvature']}, main {residual['main']}, full {residual['full']}, exact
{residual['exact']}.

## All 1000 spiral steps

Outcome: **{facts['outcome']}**, {facts['steps']} spiral steps, {facts['cutbacks']} cut-backs,
{facts['iterations']} Newton iterations ({histogram}). The axis ends at
({x:.3f}, {y:.3f}, {z:.3f}).

![trajectory](example_6_3_trajectory.png)
![iterations](example_6_3_iterations.png)
![force ratio](example_6_3_force_ratio.png)

Force ratio along the path: split into the sum of the points' tangential tractions and the rest
(the normal tractions, which STAS applies along the master facets' normals, eq. (117)),
|F_t|/|F_n| stays between {facts['own'][0]:.4f} and {facts['own'][1]:.4f}: every contact point
slides from the first spiral step on and Coulomb's limit holds. Measured against the rigid
surface's normal below the axis it varies between {facts['rigid'][0]:.3f} and
{facts['rigid'][1]:.3f}; see below.

Run times (one thread, on a machine shared with other jobs):

{wall}
## Differences from the paper, in plain words

1. **Without curvature parts: {energy['no_curvature']} against 90 iterations.** Same pattern as
   the paper (more iterations in the first steps, then 4 per step: quadratic convergence). Full
   and without-curvature tangents give the same counts here because the master surface is
   faceted: bilinear faces of a cylinder are flat, h_ij = 0, so there is no curvature part to
   drop. The exact tangent needs {energy['exact']}.
2. **Main part only: {energy['main']} against 254.** Ours costs more than the tangent with
   rotational parts ({100 * (energy['main'] / energy['no_curvature'] - 1):.0f}% more), but far
   less than in the paper (about 5 instead of 13 iterations per step, the paper's case 2 costs
   182% more than its case 1). In STAS the master Gauss point is fixed and the rigid point slides along the surface,
   so the rotational parts reduce to N delta n and T_i delta rho^i; with the small normal force
   of this soft shell (|F_n| about {facts['normal'][0]:.2f}) they are small against the main
   part. Our main part already carries the tilt of the facets against the rigid surface
   (delta g = -(delta rho) . nu / (n . nu), eq. (117) linearized). A main part with
   delta g = -(delta rho) . n, as for a projected slave point, converges only linearly: before
   this was corrected (commit "STAS paper tangent: linearize eq. (117) ...") our full and main
   tangents both needed about 19 iterations per step, the paper's order of magnitude for its
   case 2. We think the paper's case 2 lacked that tilt term; the paper does not say. The
   thickness and the penalty (both our choices) also change the size of the rotational parts.
3. **The press.** We press in one step ({facts['press']['no_curvature']} iterations without
   curvature parts); the paper's table starts with l.s. 1 = 9 iterations, which may be the press
   or the first spiral step.
4. **The force ratio against the rigid normal is not exactly 0.3.** In STAS the gap and the
   normal traction follow the master (facet) normal, eq. (117). The 16 facets are 11.25 degrees
   wide, so the facets in contact are tilted by up to 5.6 degrees against the parabola, and part
   of the normal force appears as "tangential" in the rigid surface's frame (up to
   sin 5.6 deg = 0.1 of it): the ratio changes as the contact moves across the facets of the
   half ring (from the bottom node to 45 degrees at the end of the path). Against the facets'
   own normals it is 0.300.
5. **The normal force falls along the path** (from {facts['normal'][0]:.3f} after the first
   spiral step to {facts['normal'][1]:.3f} at the end) although the indentation is held at 0.01:
   the shell is held at its straight edges and is softer for a radial load at 45 degrees than at
   the bottom. The paper shows no forces for 6.3.
6. **Equidistant motion.** Eq. (127) carries the factor 1 - 2ch = 1.001 of the offset at
   distance h = -0.01 (the body's lowest point) over to the axis. For the axis that is not
   equidistant: at x = 10 (slope 1) it would put the axis 0.44 below the curve at distance
   0.99, i.e. indent the shell by about 0.3 instead of 0.01. We prescribe the exact 0.99-offset,
   which the text describes; its x advances by about 0.9 v per step instead of 1.001 v, so our
   axis ends at x = {x:.2f} instead of 10.01 (y and the number of steps as in the paper), and
   the slip per step is 0.0219 instead of 0.0224 at the start.
"""
