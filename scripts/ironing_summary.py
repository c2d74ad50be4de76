#!/usr/bin/python3
"""Summarize ironing runs (issue 14): Newton iterations per step in developed sliding, cut-backs,
the die force level and its step-to-step jitter, from the reactions CSV and the results file.

usage: ironing_summary.py RESULTS.h5 [...]   (the CSV beside each, STEM_reactions.csv)

Developed sliding: the steps with t > 0.4 (the die has slid at least 1 of 4; the press ends at
t = 0.2). Force: the total force of the first contact pair in the CSV (the die or the ball,
issue 14's decks), or the slab_bottom reaction, signed so that the press is +z.
"""
import csv
import os
import sys

# Read-only summaries, several at once from the batch scripts' threads: h5py's file lock then
# failed now and then with "unable to lock file" (errno 11) on finished files.
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
import h5py  # noqa: E402


def sliding_metrics(t, its, fx, fz):
    """Developed sliding (t > 0.4) from per-step lists: mean iterations per step, mean Fz and
    Fx/Fz, and their step-to-step jitter max |F(k+1) - 2F(k) + F(k-1)| / mean in percent; {}
    before the run has three developed steps. Also used for CalculiX (ironing_calculix.py)."""
    d = [k for k, tk in enumerate(t) if tk > 0.4 + 1e-9]
    if len(d) <= 2:
        return {}
    out = {"its_developed": sum(its[k] for k in d) / len(d)}
    mz = sum(fz[k] for k in d) / len(d)
    ratio = [fx[k] / fz[k] for k in d]
    mr = sum(ratio) / len(ratio)
    out["Fz_mean"] = mz
    out["Fx/Fz_mean"] = mr
    out["jitter_Fz_%"] = 100 * max(abs(fz[d[i + 1]] - 2 * fz[d[i]] + fz[d[i - 1]])
                                   for i in range(1, len(d) - 1)) / abs(mz)
    if abs(mr) > 1e-12:
        out["jitter_Fx/Fz_%"] = 100 * max(abs(ratio[i + 1] - 2 * ratio[i] + ratio[i - 1])
                                          for i in range(1, len(d) - 1)) / abs(mr)
    return out


def summarize(path):
    stem = path[:-3] if path.endswith(".h5") else path
    rows = list(csv.DictReader(open(stem + "_reactions.csv")))
    with h5py.File(path, "r") as f:
        summary = dict(f["summary"].attrs) if "summary" in f else {}
        # The file's "cutbacks" table records every retried attempt, line-search retries at the
        # same step size included; the summary counts the step-size reductions alone.
        attempts = len(f["cutbacks"]) if "cutbacks" in f else 0
    t = [float(r["time"]) for r in rows]
    its = [int(r["iterations"]) for r in rows]
    pairs = [c[:-3] for c in (rows[0] if rows else {}) if c.startswith("contact_") and
             c.endswith("_Fz")]
    stem_of_force = pairs[0] if pairs else "slab_bottom"
    fz = [float(r[stem_of_force + "_Fz"]) for r in rows]
    fx = [float(r[stem_of_force + "_Fx"]) for r in rows]
    if sum(fz) < 0:  # the force on the other body of the pair: the press pushes down (+z)
        fz, fx = [-f for f in fz], [-f for f in fx]
    out = {
        "file": path,
        "outcome": summary.get("outcome", b"?"),
        "steps": len(rows),
        "final_t": t[-1] if t else 0,
        "iterations": sum(its),
        "cutbacks": int(summary.get("cutbacks", attempts)),
        "line_search_retries": int(summary.get("line_search_retries", 0)),
        "discarded_iterations": int(summary.get("discarded_iterations", 0)),
    }
    if isinstance(out["outcome"], bytes):
        out["outcome"] = out["outcome"].decode()
    out.update(sliding_metrics(t, its, fx, fz))
    return out


if __name__ == "__main__":
    for p in sys.argv[1:]:
        s = summarize(p)
        print("  ".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}"
                        for k, v in s.items()))
