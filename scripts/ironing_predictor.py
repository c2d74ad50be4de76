#!/usr/bin/python3
"""The ironing decks of issue 14 with and without `newton predictor=extrapolate`: Newton
iterations per step in developed sliding (t > 0.4), retries and cut-backs, the final time and
the mean die force of each run, as the Markdown table of docs/verification/sliding.md ("Seventh
session"). One command from a built checkout:

    /usr/bin/python3 scripts/ironing_predictor.py [--only SUBSTRING[,SUBSTRING...]]
        [--limit SECONDS] [--jobs N] [--tangent full|exact] [--extrapolate-only]

Each run gets --threads 1 and is interrupted (SIGINT: its converged steps are kept) after
--limit seconds (default 200). Besides the committed decks it runs the variants the table
names (v): STS with `surface=smooth` added to a faceted deck (mu = 0.6; the smoothed mu = 0.3
equal and mu = 0 decks are committed since the thirty-ninth session), NTS with the energy criterion
(`converge=residual` removed) and STAS without the line search. The variants and results go to
--work (default /tmp/ironing_predictor); nothing is written into the source tree.
--tangent replaces every deck's contact tangent (the decks have `tangent=exact`), for the
report's table by tangent option; --extrapolate-only runs only the predictor column.
About 40 minutes on 2 cores for everything (--jobs 2).
"""
import argparse
import concurrent.futures
import os
import re
import signal
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import ironing_summary  # noqa: E402

DECKS = os.path.join(ROOT, "input", "stress", "ironing")

# (name of the variant, deck it is made from, edit of its text)
VARIANTS = [
    ("sts_mu06_wide_smooth", "ironing_sts_mu06_wide", ("name=die", "name=die surface=smooth")),
    ("nts_mu03_wide_smooth_energy", "ironing_nts_mu03_wide_smooth_residual",
     ("  newton converge=residual residual=1e-8\n", "")),
    ("nts_mu03_equal_smooth_energy", "ironing_nts_mu03_equal_smooth_residual",
     ("  newton converge=residual residual=1e-8\n", "")),
    ("stas_mu03_no_line_search", "ironing_stas_mu03", ("  newton line_search=yes\n", "")),
]


def absolute_paths(text, deck_dir=DECKS):
    """A deck of input/stress/*/ with its includes (beside it) and its mesh (in meshes/) given
    absolute paths, so that it runs from --work (this script's decks, and ball_cases.py's)."""
    text = re.sub(r'^include "([^"/]+)"',
                  lambda m: f'include "{os.path.join(deck_dir, m.group(1))}"', text, flags=re.M)
    return text.replace('"../../../meshes/', '"' + os.path.join(ROOT, "meshes") + "/")


def with_predictor(text):
    return re.sub(r"^solve(.*)$", r"solve\1\n  newton predictor=extrapolate", text, count=1,
                  flags=re.M)


def cases():
    """(name, deck text) of every deck and variant."""
    out = []
    for deck in sorted(os.listdir(DECKS)):
        if deck.endswith(".deck"):
            out.append((deck[:-5], absolute_paths(open(os.path.join(DECKS, deck)).read())))
    for name, source, (old, new) in VARIANTS:
        text = absolute_paths(open(os.path.join(DECKS, source + ".deck")).read())
        if old not in text:
            sys.exit(f"variant {name}: '{old.strip()}' not in {source}.deck")
        out.append((name + " (v)", text.replace(old, new, 1)))
    return out


def run(covcontact, work, name, text, limit):
    stem = os.path.join(work, re.sub(r"[^A-Za-z0-9_]", "_", name))
    open(stem + ".deck", "w").write(text)
    process = subprocess.Popen([covcontact, "run", stem + ".deck", "-o", stem + ".h5",
                                "--threads", "1"], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
    try:
        process.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        process.send_signal(signal.SIGINT)
        process.communicate()
    return report(stem)


def report(stem):
    """The run's summary (ironing_summary.py), line-search retries and cut-backs from the file."""
    return ironing_summary.summarize(stem + ".h5") if os.path.exists(stem + ".h5") else {}


def cell(result):
    developed = result.get("its_developed")
    text = f"{developed:.2f}" if developed is not None else "-"
    if result.get("final_t", 0) < 1 - 1e-9:
        text += f" (stopped at t = {result.get('final_t', 0):.3g})"
    return text


def iterations_cell(result):
    """Newton iterations of the converged steps (+ those of failed attempts, line-search
    retries / cut-backs)."""
    return (f"{result.get('iterations', 0)} (+{result.get('discarded_iterations', 0)}, "
            f"{result.get('line_search_retries', 0)} / {result.get('cutbacks', 0)})")


def selected(name, only):
    """--only: the case names containing any of the comma-separated substrings (one ending in
    '$': the names ending in it)."""
    return any(name.endswith(part[:-1]) if part.endswith("$") else part in name
               for part in only.split(","))


def parse_batch_args(doc, work, limit, extra=None):
    """The command line of a batch of decks (this script, ball_cases.py); extra(parser) adds a
    script's own options."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--covcontact", default=os.path.join(ROOT, "build", "src", "app",
                                                             "covcontact"))
    parser.add_argument("--work", default=work)
    parser.add_argument("--only", default="",
                        help="only the cases whose name contains this (or one of these, "
                             "comma-separated; 'x$': ending in x)")
    parser.add_argument("--limit", type=float, default=limit, help="seconds per run")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--report-only", action="store_true",
                        help="tabulate the results already in --work without running")
    if extra:
        extra(parser)
    return parser.parse_args()


def tangent_options(parser):
    parser.add_argument("--tangent", choices=("full", "exact"),
                        help="every deck's contact tangent (default: the deck's, exact)")
    parser.add_argument("--extrapolate-only", action="store_true",
                        help="only the runs with predictor=extrapolate")


def main():
    args = parse_batch_args(__doc__, "/tmp/ironing_predictor", 200, tangent_options)
    os.makedirs(args.work, exist_ok=True)
    todo = [(name, text) for name, text in cases() if selected(name, args.only)]
    if args.tangent:
        for name, text in todo:
            if "tangent=exact" not in text:
                sys.exit(f"{name}: no tangent=exact to replace")
        todo = [(name, text.replace("tangent=exact", f"tangent={args.tangent}"))
                for name, text in todo]
    labels = ("extrapolate",) if args.extrapolate_only else ("default", "extrapolate")
    jobs = []
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for name, text in todo:
            for label, variant in (("default", text), ("extrapolate", with_predictor(text))):
                if label not in labels:
                    continue
                stem = f"{name}_{label}"
                jobs.append((name, label, pool.submit(
                    report, os.path.join(args.work, re.sub(r"[^A-Za-z0-9_]", "_", stem)))
                    if args.report_only else
                    pool.submit(run, args.covcontact, args.work, stem, variant, args.limit)))
    results = {(name, label): job.result() for name, label, job in jobs}
    both = len(labels) == 2
    print("| deck |" + (" default: developed |" if both else "") + " extrapolate: developed | "
          "extrapolate: its (+discarded, line-search retries / cut-backs), mean Fz |")
    print("|---|---|---|" + ("---|" if both else ""))
    for name, _ in todo:
        after = results[(name, "extrapolate")]
        before = f" {cell(results[(name, 'default')])} |" if both else ""
        fz = after.get("Fz_mean")
        print(f"| `{name}` |{before} {cell(after)} | {iterations_cell(after)}"
              + (f", {abs(fz):.2f}" if fz is not None else "") + " |")


if __name__ == "__main__":
    main()
