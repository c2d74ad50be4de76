"""Paper example 6.2: parabolic block on a parabolic base, NTS, 18-node solid-shells (issue 5).

Runs input/paper/parabolic_block_6_2{a,b,c_*}.deck and writes to docs/paper/ the plots matching
Figs. 9, 10, 12 and 13, Table 4 (paper's numbers beside ours, plus the exact tangent, at the
relative energy criterion and at relative residual <= 1e-10) and example_6_2.md's generated part.
"""

import h5py
import matplotlib
import numpy as np

from .common import iterations_per_step, markdown_table, residual_variant

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PARABOLA_C = 0.03          # z = c x^2, eq. (113)
PRESS_STEPS = 7            # w = 0.007 in 7 load steps
SLIDE_INCREMENT_B = 2.5e-5  # Delta u of 6.2(b)
FRICTION = 0.3
PAIR = "interface"
FRONT_ROW_TOLERANCE = 1e-9  # y of the plotted row (the front face y = 0)
ZERO_FORCE = 1e-9           # a nodal normal force below this (of the largest) counts as zero
TANGENTS = ["full", "no_curvature", "main", "exact"]
# Table 4 as printed: (first step, last step, iterations per step, cumulative).
PAPER_TABLE4 = {
    "full": [(1, 1, 6, 6), (2, 2, 5, 11), (3, 3, 5, 16), (4, 18, 4, 76), (19, 20, 5, 86)],
    "no_curvature": [(1, 1, 6, 6), (2, 2, 5, 11), (3, 3, 5, 16), (4, 16, 4, 68),
                     (17, 20, 3, 88)],
    "main": [(1, 9, 6, 54), (10, 12, 7, 75), (13, 15, 8, 99), (15, 17, 9, 126),
             (18, 20, 10, 156)],
}


def reproduce(context):
    paper = context.repo / "input" / "paper"
    press = context.run(paper / "parabolic_block_6_2a.deck", "parabolic_block_6_2a")
    motion = context.run(paper / "parabolic_block_6_2b.deck", "parabolic_block_6_2b")
    energy_runs, residual_runs = {}, {}
    for tangent in TANGENTS:
        deck = paper / f"parabolic_block_6_2c_{tangent}.deck"
        energy_runs[tangent] = context.run(deck, f"parabolic_block_6_2c_{tangent}")
        residual_deck = residual_variant(deck, context.work)
        residual_runs[tangent] = context.run(residual_deck, residual_deck.stem)
    findings = {}
    findings["press"] = plot_press(press, context.docs / "example_6_2_fig9.png")
    findings["motion"] = plot_motion(motion, context.docs)
    tables = table4(energy_runs, residual_runs)
    walls = {name: seconds for name, seconds in context.wall_seconds.items()
             if name.startswith("parabolic_block_6_2")}
    write_generated(context.docs / "example_6_2_results.md", findings, tables, walls)


class Surface:
    """The front row (y = 0) of the contact surface: block bottom nodes and slave nodes by x."""

    def __init__(self, results):
        with h5py.File(results, "r") as f:
            coordinates = f["mesh/coordinates"][...]
            bottom = f["mesh/node_sets/block_bottom/nodes"][...]
            first = f["steps"][sorted(f["steps"])[0]]
            slaves = first[f"contact/{PAIR}/slave_nodes"][...]
        self.block_nodes = front_row(coordinates, bottom)
        self.x = coordinates[self.block_nodes, 0]
        alpha = np.arctan(2 * PARABOLA_C * self.x)  # slope angle, reference configuration
        self.tangent = np.stack([np.cos(alpha), np.zeros_like(alpha), np.sin(alpha)], axis=1)
        self.normal = np.stack([-np.sin(alpha), np.zeros_like(alpha), np.cos(alpha)], axis=1)
        # Slave nodes at each x (all rows across y): their forces are summed per cross-section.
        slave_x = coordinates[slaves, 0]
        self.slave_columns = [np.flatnonzero(np.isclose(slave_x, x, atol=1e-6)) for x in self.x]

    def tangential_displacement(self, step):
        """u_tau = u_x cos(alpha) + u_z sin(alpha) of the block's bottom nodes."""
        displacement = step["displacement"][...][self.block_nodes]
        return np.einsum("ij,ij->i", displacement, self.tangent)

    def nodal_forces(self, step):
        """(F_tau, F_n) per x on the block (minus the slave force), summed across y."""
        force = -step[f"contact/{PAIR}/slave_nodal_force"][...]
        column = np.array([force[c].sum(axis=0) for c in self.slave_columns])
        tangential = np.einsum("ij,ij->i", column, self.tangent)
        return tangential, np.einsum("ij,ij->i", column, self.normal)


def front_row(coordinates, nodes):
    row = nodes[np.abs(coordinates[nodes, 1]) < FRONT_ROW_TOLERANCE]
    return row[np.argsort(coordinates[row, 0])]


def states_by_x(step, surface):
    """Contact state (0 open, 1 stick, 2 slip) of the front-row slave node at each x."""
    position = step[f"contact/{PAIR}/position"][...]
    state = step[f"contact/{PAIR}/state"][...]
    front = np.abs(position[:, 1]) < FRONT_ROW_TOLERANCE
    order = np.argsort(position[front, 0])
    return position[front, 0][order], state[front][order]


def plot_press(results, png):
    """Fig. 9: u_tau over x after each pressing step; returns the stick zone and the symmetry."""
    surface = Surface(results)
    figure, axes = plt.subplots(figsize=(7, 4.5))
    with h5py.File(results, "r") as f:
        names = sorted(f["steps"])
        for name in names:
            step = f["steps"][name]
            w = 1e-3 * step.attrs["time"]
            axes.plot(surface.x, surface.tangential_displacement(step), marker=".",
                      label=f"w = {w:.3f}")
        last = f["steps"][names[-1]]
        u_tau = surface.tangential_displacement(last)
        x_state, state = states_by_x(last, surface)
        f_tau, f_n = surface.nodal_forces(last)
    finish(axes, figure, png, "u_tau", "Fig. 9: tangential displacement, vertical loading")
    stick_x = x_state[state == 1]
    asymmetry = np.max(np.abs(u_tau + u_tau[::-1])) / np.max(np.abs(u_tau))
    return {"stick_from": stick_x.min(), "stick_to": stick_x.max(),
            "slip_x": x_state[state == 2], "asymmetry": asymmetry,
            "ratio": f_tau / np.where(f_n > 0, f_n, np.nan), "x": surface.x}


def motion_steps(results):
    """(u, step name) of every written step of 6.2(b) after the pressing."""
    with h5py.File(results, "r") as f:
        return [(SLIDE_INCREMENT_B * (f["steps"][n].attrs["time"] - PRESS_STEPS), n)
                for n in sorted(f["steps"]) if f["steps"][n].attrs["time"] >= PRESS_STEPS - 1e-9]


def at_load(results, loads):
    by_u = motion_steps(results)
    return [min(by_u, key=lambda pair: abs(pair[0] - u)) for u in loads]


def plot_motion(results, docs):
    """Figs. 10, 12, 13 and the contact-loss onset of 6.2(b)."""
    surface = Surface(results)
    findings = {}
    with h5py.File(results, "r") as f:
        figure, axes = plt.subplots(figsize=(7, 4.5))
        for u, name in at_load(results, [0, 1e-3, 2e-3, 3e-3, 5e-3]):
            axes.plot(surface.x, surface.tangential_displacement(f["steps"][name]), marker=".",
                      label=f"u = {u:.1e}")
        finish(axes, figure, docs / "example_6_2_fig10.png", "u_tau",
               "Fig. 10: phase 1, the right sliding zone vanishes")

        figure, axes = plt.subplots(figsize=(7, 4.5))
        for u, name in at_load(results, [5e-3, 10e-3, 15e-3, 20e-3, 25e-3, 30e-3]):
            step = f["steps"][name]
            u_tau = surface.tangential_displacement(step)
            line, = axes.plot(surface.x, u_tau, label=f"u = {u:.1e}")
            for k in np.flatnonzero(np.convolve(without_contact(surface, step), [1, 1]) == 2) - 1:
                axes.plot(surface.x[k:k + 2], u_tau[k:k + 2], color=line.get_color(), linewidth=4)
        finish(axes, figure, docs / "example_6_2_fig12.png", "u_tau",
               "Fig. 12: phase 2 (thick: nodes without normal force)")

        figure, axes = plt.subplots(figsize=(7, 4.5))
        for u, name in at_load(results, [0, 1e-3, 2e-3, 3e-3, 5e-3, 10e-3]):
            f_tau, f_n = surface.nodal_forces(f["steps"][name])
            ratio = np.where(f_n > 0, f_tau / np.where(f_n > 0, f_n, 1), np.nan)
            axes.plot(surface.x, ratio, marker=".", label=f"u = {u:.1e}")
        for limit in (FRICTION, -FRICTION):
            axes.axhline(limit, color="grey", linestyle=":")
        finish(axes, figure, docs / "example_6_2_fig13.png", "F_tau / F_n",
               "Fig. 13: ratio of nodal contact forces")

        findings["contact_loss_from"] = contact_loss_onset(f, surface, motion_steps(results))
        findings["right_slip_gone_at"] = right_slip_vanishes(f, surface, motion_steps(results))
        last = motion_steps(results)[-1][1]
        findings["lost_at_end"] = surface.x[without_contact(surface, f["steps"][last])]
    return findings


def without_contact(surface, step):
    """Nodes (by x) whose normal force is zero: contact lost (the thick lines of Fig. 12)."""
    f_n = surface.nodal_forces(step)[1]
    return f_n <= ZERO_FORCE * np.abs(f_n).max()


def contact_loss_onset(f, surface, by_u):
    """First u with a node without normal force, and the x of those nodes."""
    for u, name in by_u:
        lost = without_contact(surface, f["steps"][name])
        if np.any(lost):
            return u, surface.x[lost]
    return None, []


def right_slip_vanishes(f, surface, by_u):
    for u, name in by_u:
        x_state, state = states_by_x(f["steps"][name], surface)
        if not np.any((state == 2) & (x_state > 0)):
            return u
    return None


def finish(axes, figure, png, ylabel, title):
    axes.set_xlabel("x")
    axes.set_ylabel(ylabel)
    axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(png, dpi=120)
    plt.close(figure)


def sliding_iterations(results):
    return iterations_per_step(results)[PRESS_STEPS:]


def grouped(counts):
    """Rows (steps, iterations per step, cumulative) of equal consecutive counts (Table 4)."""
    rows, total, start = [], 0, 0
    for k in range(1, len(counts) + 1):
        if k == len(counts) or counts[k] != counts[start]:
            total += counts[start] * (k - start)
            label = f"{start + 1}" if k - start == 1 else f"{start + 1}-{k}"
            rows.append((label, counts[start], total))
            start = k
    return rows


def table4(energy_runs, residual_runs):
    energy = {t: sliding_iterations(r) for t, r in energy_runs.items()}
    residual = {t: sliding_iterations(r) for t, r in residual_runs.items()}
    summary = [(t, PAPER_TABLE4[t][-1][3] if t in PAPER_TABLE4 else "-", sum(energy[t]),
                sum(residual[t])) for t in TANGENTS]
    text = markdown_table(["tangent", "paper (cum.)", "ours, energy <= 1e-16",
                           "ours, residual <= 1e-10"], summary)
    for t in TANGENTS:
        text += f"\n**{t}** (ours, energy criterion; paper's rows beside)\n\n"
        ours = grouped(energy[t])
        paper = [(f"{a}" if a == b else f"{a}-{b}", n, cum)
                 for a, b, n, cum in PAPER_TABLE4.get(t, [])]
        rows = [(o[0], o[1], o[2], *(paper[k] if k < len(paper) else ("", "", "")))
                for k, o in enumerate(ours)]
        rows += [("", "", "", *p) for p in paper[len(ours):]]
        text += markdown_table(["l.s.", "it./l.s.", "cum.", "paper l.s.", "paper it./l.s.",
                                "paper cum."], rows)
    per_step = [(k + 1, *(energy[t][k] for t in TANGENTS), *(residual[t][k] for t in TANGENTS))
                for k in range(len(energy["full"]))]
    text += "\nPer sliding step (E: energy criterion, R: residual criterion):\n\n"
    header = ["l.s."] + [f"{t} (E)" for t in TANGENTS] + [f"{t} (R)" for t in TANGENTS]
    text += markdown_table(header, per_step)
    return text


def write_generated(md, findings, tables, walls):
    press, motion = findings["press"], findings["motion"]
    lines = ["<!-- generated by scripts/reproduce_paper.py --only 6.2; do not edit -->",
             "## Measured (generated)", "",
             f"- 6.2(a), w = 0.007: stick zone {press['stick_from']:.2f} <= x <= "
             f"{press['stick_to']:.2f}; mirror asymmetry of u_tau "
             f"max|u(x) + u(-x)| / max|u| = {press['asymmetry']:.1e}.",
             "- 6.2(a): F_tau/F_n at x = " + ", ".join(
                 f"{x:.0f}: {r:.3f}" for x, r in zip(press["x"], press["ratio"])
                 if x >= 0 and np.isclose(x, round(x))) + ".",
             f"- 6.2(b): the right sliding zone has vanished at u = "
             f"{motion['right_slip_gone_at']}; contact loss (a node with zero normal force) from "
             f"u = {motion['contact_loss_from'][0]:.2e}, at x = "
             f"{list(np.round(motion['contact_loss_from'][1], 2))}.",
             "- 6.2(b): nodes without contact at u = 0.03: x = "
             f"{list(np.round(motion['lost_at_end'], 2))}.",
             "",
             "### Table 4", "", tables, "", "### Wall time (1 thread)", "",
             markdown_table(["run", "wall seconds"],
                            [(n, f"{s:.1f}") for n, s in sorted(walls.items())])]
    md.write_text("\n".join(lines) + "\n")
