#!/usr/bin/python3
"""The ball-on-block decks of issue 14 (`input/stress/ball/`): Newton iterations per step in
developed sliding (t > 0.4), line-search retries, cut-backs, the final time, the mean contact
force and Fx/Fz of each run (meaningless for the *_arc decks, whose path turns), as the
Markdown table of docs/verification/sliding.md ("Twentieth session"). One command from a built
checkout:

    /usr/bin/python3 scripts/ball_cases.py [--only SUBSTRING] [--limit SECONDS] [--jobs N]

Each run gets --threads 1 and is interrupted (SIGINT: its converged steps are kept) after
--limit seconds (default 300). The decks carry their own solution control
(`predictor=extrapolate`); results go to --work (default /tmp/ball_cases), nothing into the
source tree. About 6 minutes on 2 cores for everything (--jobs 2).
"""
import concurrent.futures
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import ironing_predictor  # noqa: E402

DECKS = os.path.join(ROOT, "input", "stress", "ball")


def main():
    args = ironing_predictor.parse_batch_args(__doc__, "/tmp/ball_cases", 300)
    os.makedirs(args.work, exist_ok=True)
    names = sorted(d[:-5] for d in os.listdir(DECKS) if d.endswith(".deck") and ironing_predictor.selected(d, args.only))
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        jobs = {name: pool.submit(ironing_predictor.report, os.path.join(args.work, name))
                if args.report_only else
                pool.submit(ironing_predictor.run, args.covcontact, args.work, name,
                            ironing_predictor.absolute_paths(
                                open(os.path.join(DECKS, name + ".deck")).read(), DECKS),
                            args.limit)
                for name in names}
    print("| deck | developed | its (+discarded, line-search retries / cut-backs) | mean Fz | "
          "mean Fx/Fz |")
    print("|---|---|---|---|---|")
    for name in names:
        result = jobs[name].result()
        fz, ratio = result.get("Fz_mean"), result.get("Fx/Fz_mean")
        print(f"| `{name}` | {ironing_predictor.cell(result)} | "
              f"{ironing_predictor.iterations_cell(result)} | "
              + (f"{fz:.4g}" if fz is not None else "-") + " | "
              + (f"{abs(ratio):.3f}" if ratio is not None else "-") + " |")


if __name__ == "__main__":
    main()
