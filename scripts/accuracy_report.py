"""Writes docs/verification/accuracy.md and its plots from the run cache of error_vs_time.py.

Tables per case and sweep (errors, Newton iterations, CPU and wall time), observed orders (least
squares slopes of log error against log element size and log CPU time), log-log plots of error
against CPU time per contact kind, the penalty-convergence plot and example 6.1 against its
finest run. The narrative (what limits each case, recommended settings) is in accuracy_notes.py.
"""
import math

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

import accuracy_notes  # noqa: E402

# Per case: (quantity suffix in /verification, column label, how to show the error).
# "rel": signed relative error in %; "elements": relative error and |error| / h; "abs": absolute.
HERTZ_SPHERE = [("force:z", "P(δ)", "rel"), ("radius", "a", "elements"),
                ("centre_pressure", "p0 centre", "rel"), ("peak_pressure", "p0 max", "rel"),
                ("penetration", "max penetration", "abs")]
QUANTITIES = {
    "hertz_rigid_sphere": HERTZ_SPHERE,
    "hertz_elastic_sphere": HERTZ_SPHERE,
    "hertz_elastic_sphere_nts": HERTZ_SPHERE,
    "hertz_elastic_sphere_segments": HERTZ_SPHERE,
    "hertz_elastic_sphere_smooth": HERTZ_SPHERE,
    "hertz_elastic_sphere_smooth_segments": HERTZ_SPHERE,
    "hertz_elastic_sphere_augmented": HERTZ_SPHERE,
    "hertz_cylinder": [("half_width", "b", "elements"), ("centre_pressure", "p0 centre", "rel"),
                       ("peak_pressure", "p0 max", "rel")],
    "cattaneo_mindlin_sphere": [("stick_radius", "c", "elements"), ("force:x", "Q(δt)", "rel"),
                                ("force:z", "P(δ)", "rel"), ("radius", "a", "elements"),
                                ("centre_pressure", "p0 centre", "rel")],
    "cattaneo_mindlin_cylinder": [("stick_half_width", "c", "elements"), ("half_width", "b", "elements"),
                                  ("centre_pressure", "p0 centre", "rel")],
    "patch_sts": [("pressure_deviation", "point pressure dev.", "abs"),
                  ("nodal_pressure_deviation", "nodal pressure dev.", "abs"),
                  ("reaction:upper_top:z", "total force", "rel")],
    "example_6_1": [("Fx", "F_x(t) (tangential)", "rel"), ("Fy", "F_y(t) (normal)", "rel")],
}
QUANTITIES["patch_nts"] = QUANTITIES["patch_sts"]
QUANTITIES["patch_sts_matching"] = QUANTITIES["patch_sts"]
QUANTITIES["patch_sts_segments"] = QUANTITIES["patch_sts"]

KINDS = {
    "STAS": ["hertz_rigid_sphere", "hertz_cylinder"],
    "STS": ["hertz_elastic_sphere", "cattaneo_mindlin_sphere", "cattaneo_mindlin_cylinder", "patch_sts",
            "example_6_1"],
    "NTS": ["hertz_elastic_sphere_nts", "patch_nts"],
    "STS-segments": ["hertz_elastic_sphere", "hertz_elastic_sphere_segments", "patch_sts",
                     "patch_sts_segments"],
    "STS-smooth": ["hertz_elastic_sphere", "hertz_elastic_sphere_smooth",
                   "hertz_elastic_sphere_smooth_segments"],
    "STS-augmented": ["hertz_elastic_sphere", "hertz_elastic_sphere_augmented"],
}
SWEEP_TITLES = {"mesh": "mesh levels", "penalty": "penalty (alpha = eps_N h / E; patch tests and example 6.1: eps_N)",
                "steps": "load steps", "domain": "domain size", "points": "Gauss points per direction"}


def reference_of(entry, suffix):
    for quantity, values in entry.get("references", {}).items():
        if quantity.endswith(":" + suffix) or quantity == suffix:
            return values
    return None


def example_errors(entries):
    """Example 6.1: max over the sliding phase of |F(t) - F_ref(t)| / max |F_ref|, per sweep,
    against the sweep's finest run (largest value)."""
    by_sweep = {}
    for entry in entries:
        by_sweep.setdefault(entry["sweep"], []).append(entry)
    for runs in by_sweep.values():
        finished = [r for r in runs if r.get("outcome") == "completed"]
        if not finished:
            continue
        reference = max(finished, key=lambda r: r["value"])
        ref_time = np.array(reference["history"]["time"])
        ref_force = np.array(reference["history"]["force"])
        sliding = ref_time > 1
        for run in finished:
            run["references"] = {}
            if run is reference:
                continue
            time = np.array(run["history"]["time"])
            force = np.array(run["history"]["force"])
            mask = time > 1
            for name, component in (("Fx", 0), ("Fy", 1)):
                scale = np.abs(ref_force[sliding, component]).max()
                interpolated = np.interp(time[mask], ref_time, ref_force[:, component])
                error = np.abs(force[mask, component] - interpolated).max() / scale
                run["references"][name] = {"relative_error": error, "max_relative_error": error,
                                           "error": error * scale}


def error_text(values, style, h):
    if values is None:
        return "-"
    relative, error = values["relative_error"], values["error"]
    if style == "abs" or math.isnan(relative):
        return f"{error:.2g}"
    text = f"{100 * relative:+.3g}%"
    if style == "elements" and h:
        text += f" ({abs(error) / h:.2f} h)"
    return text


def observed_order(xs, ys):
    points = [(math.log(x), math.log(abs(y))) for x, y in zip(xs, ys) if x and y and abs(y) > 0]
    if len(points) < 3:
        return None
    slope, _ = np.polyfit([p[0] for p in points], [p[1] for p in points], 1)
    return slope


def sweep_table(case, sweep, runs):
    quantities = QUANTITIES[case]
    header = ["value", "h", "Newton", "cut-backs", "CPU s", "wall s"] + [q[1] for q in quantities]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for run in sorted(runs, key=lambda r: r["value"]):
        if run.get("outcome") != "completed":
            lines.append(f"| {run['value']:g} | | failed (exit {run['exit']}) |" + " |" * (len(header) - 3))
            continue
        h = run.get("h")
        value = f"{run['value']:g}" + (" (deck)" if run.get("target") else "")
        cells = [value, f"{h:.3g}" if h else "-", str(run["iterations"]), str(run["cutbacks"]),
                 f"{run['cpu']:.1f}", f"{run['wall']:.1f}"]
        cells += [error_text(reference_of(run, q[0]), q[2], h) for q in quantities]
        lines.append("| " + " | ".join(cells) + " |")
    if sweep == "mesh":
        orders = []
        for suffix, label, _ in quantities:
            done = [r for r in runs if r.get("outcome") == "completed" and reference_of(r, suffix)]
            errors = [reference_of(r, suffix)["error"] for r in done]
            by_size = observed_order([r.get("h") or 1 / r["value"] for r in done], errors)
            by_time = observed_order([r["cpu"] for r in done], errors)
            if by_size is not None:
                orders.append(f"{label}: |error| ~ h^{by_size:.2f} ~ CPU^{by_time:.2f}")
        if orders:
            lines.append("")
            lines.append("Observed orders (least squares over the levels): " + "; ".join(orders) + ".")
    return "\n".join(lines)


# The quantities drawn in the per-kind plots (all are in the tables): each case's targets.
PLOTTED = {"force:z", "radius", "centre_pressure", "peak_pressure", "half_width", "stick_radius",
           "stick_half_width", "force:x", "pressure_deviation", "nodal_pressure_deviation", "Fx"}


def plot_kind(kind, cases, by_case, directory):
    figure, axes = plt.subplots(figsize=(9, 4.5))
    markers = iter("osd^v<>ph*" * 4)
    colors = iter(plt.cm.tab20.colors * 2)  # one colour per curve: the default cycle has only 10
    for case in cases:
        runs = [r for r in by_case.get(case, []) if r["sweep"] == "mesh" and r.get("outcome") == "completed"]
        for suffix, label, style in QUANTITIES[case]:
            if suffix not in PLOTTED:
                continue
            points = sorted((r["cpu"], abs(reference_of(r, suffix)["relative_error"] if style != "abs"
                                           else reference_of(r, suffix)["error"]))
                            for r in runs if reference_of(r, suffix))
            points = [p for p in points if p[1] > 0 and not math.isnan(p[1])]
            if len(points) >= 2:
                order = observed_order(*zip(*points))
                slope = f" (~CPU^{order:.2f})" if order is not None else ""
                axes.loglog(*zip(*points), marker=next(markers), color=next(colors),
                            label=f"{case}: {label}{slope}")
    axes.set_xlabel("CPU time of the run [s] (one core)")
    axes.set_ylabel("|relative error| (deviation for patch tests)")
    axes.set_title(f"{kind}: error against run time over mesh levels")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    figure.tight_layout()
    path = directory / f"error_vs_time_{kind.lower()}.png"
    figure.savefig(path, dpi=90)
    plt.close(figure)
    return path.name


# The patch test's reaction without penalty compliance, E W^2 d / (2 T) (patch_test_sts_matching.deck):
# the penalty sweep's reference includes the penalty in series, so its error is measured from this.
PATCH_RIGID_FORCE = 1e-3
# The indentation of hertz_elastic_sphere.deck (uz = -0.0096 t, one step to t = 1).
ELASTIC_DELTA = 0.0096


def penalty_error(values, style):
    if style == "abs":
        return abs(values["error"])
    if style == "rigid":
        return abs(abs(values["measured"]) - PATCH_RIGID_FORCE)
    return abs(values["relative_error"])


def plot_penalty(by_case, directory):
    figure, axes = plt.subplots(figsize=(8, 5))
    slopes = {}
    hertz = [r for r in by_case.get("hertz_rigid_sphere", []) if r["sweep"] == "penalty"
             and r.get("outcome") == "completed"]
    patch = [r for r in by_case.get("patch_sts_matching", []) if r["sweep"] == "penalty"
             and r.get("outcome") == "completed"]
    def penalty_runs(case):
        return [r for r in by_case.get(case, []) if r["sweep"] == "penalty" and r.get("outcome") == "completed"]
    elastic, augmented = penalty_runs("hertz_elastic_sphere"), penalty_runs("hertz_elastic_sphere_augmented")
    series = [(hertz, "penetration", "Hertz STAS: max penetration / delta", 0.01, "abs"),
              (hertz, "force:z", "Hertz STAS: P(delta) error", 1, "rel"),
              (patch, "reaction:upper_top:z", "patch STS, matching: force error", PATCH_RIGID_FORCE, "rigid"),
              (elastic, "penetration", "Hertz STS m=4, penalty: max penetration / delta", ELASTIC_DELTA, "abs"),
              (augmented, "penetration", "Hertz STS m=4, augmented: max penetration / delta", ELASTIC_DELTA,
               "abs"),
              (elastic, "force:z", "Hertz STS m=4, penalty: P(delta) error", 1, "rel"),
              (augmented, "force:z", "Hertz STS m=4, augmented: P(delta) error", 1, "rel")]
    for runs, suffix, label, scale, style in series:
        points = sorted((r["value"], penalty_error(reference_of(r, suffix), style) / scale)
                        for r in runs if reference_of(r, suffix))
        if len(points) >= 2:
            axes.loglog(*zip(*points), marker="o", label=label)
            slopes[label] = observed_order(*zip(*points))
    axes.set_xlabel("penalty (Hertz: alpha = eps_N h / E; patch: eps_N)")
    axes.set_xscale("log")
    axes.set_ylabel("error")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(directory / "penalty_convergence.png", dpi=90)
    plt.close(figure)
    return slopes


def plot_example(runs, directory):
    figure, axes = plt.subplots(figsize=(6, 4))
    for sweep, marker in (("mesh", "o"), ("steps", "s"), ("penalty", "d")):
        points = sorted((r["cpu"], reference_of(r, "Fx")["relative_error"]) for r in runs
                        if r["sweep"] == sweep and reference_of(r, "Fx"))
        points = [p for p in points if p[1] > 0]
        if len(points) >= 2:
            axes.loglog(*zip(*points), marker=marker, label=f"{sweep} (F_x history)")
    axes.set_xlabel("CPU time of the run [s] (one core)")
    axes.set_ylabel("max |F_x - F_x,ref| / max |F_x,ref|")
    axes.set_title("Example 6.1(a), STS, against the sweep's finest run")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(directory / "example_6_1.png", dpi=90)
    plt.close(figure)


def write(cache, directory):
    directory.mkdir(parents=True, exist_ok=True)
    by_case = {}
    for entry in cache.values():
        by_case.setdefault(entry["case"], []).append(entry)
    if "example_6_1" in by_case:
        example_errors(by_case["example_6_1"])
    sections = [accuracy_notes.INTRODUCTION]
    for kind, cases in KINDS.items():
        sections.append(f"![{kind}]({plot_kind(kind, cases, by_case, directory)})")
    slopes = plot_penalty(by_case, directory)
    if "example_6_1" in by_case:
        plot_example(by_case["example_6_1"], directory)
    for case, title in accuracy_notes.CASE_TITLES.items():
        if case not in by_case:
            continue
        sections.append(f"## {title}\n\n{accuracy_notes.CASE_NOTES.get(case, '')}")
        sweeps = {}
        for run in by_case[case]:
            sweeps.setdefault(run["sweep"], []).append(run)
        for sweep, runs in sweeps.items():
            sections.append(f"### {case}: {SWEEP_TITLES[sweep]}\n\n{sweep_table(case, sweep, runs)}")
        if case == "hertz_rigid_sphere" and slopes:
            text = "; ".join(f"{label}: slope {slope:.2f}" for label, slope in slopes.items() if slope)
            sections.append(f"![penalty convergence](penalty_convergence.png)\n\nPenalty convergence: {text}.")
        if case == "example_6_1":
            sections.append("![example 6.1](example_6_1.png)")
    sections.append(accuracy_notes.RECOMMENDATIONS)
    (directory / "accuracy.md").write_text("\n\n".join(sections) + "\n")
