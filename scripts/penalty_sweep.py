#!/usr/bin/python3
"""Penalty sweep (issue 16, part 3): the same contact problem at contact penalties from 1e-2 to
1e4 times the automatic one (eps_scale=), with penalty and augmented-Lagrangian enforcement;
prints one Markdown table per case with the cost (converged and discarded Newton iterations,
line-search and continuation retries, cut-backs) and the results (press force, final drag
force, deepest penetration), for docs/verification/augmented_lagrangian.md.

Cases:
  block  input/verification/contact/augmented_block.deck, the block of
         tests/regression/contact/test_augmented_lagrangian.cpp (4 x 2
         elements pressed onto an elastic base by 4e-3, dragged by 4e-3 in 4 steps; residual
         criterion 1e-10); under a second per run.
  6.1b   input/paper/sliding_block_6_1b_exact.deck with its eps_n/eps_t replaced by eps_scale=
         (eps_ref = 2.1e5, the paper's own value); 21 steps.
  hertz  input/verification/contact/hertz_elastic_sphere.deck at mesh level m (--hertz-m, default
         6) with eps_n replaced by eps_scale=; one load step; minutes per run.

Usage: scripts/penalty_sweep.py --covcontact build/src/app/covcontact --work /tmp/sweep
                                [--cases block,6.1b] [--scales 0.01,0.1,1,10,100,1000,10000]
                                [--newton "aug_inner=0.1"]
--newton adds options to each deck's newton line (one is added after `solve` if there is none),
e.g. the augmented Lagrangian's inexact re-solves; the file names then carry a tag of them.
Runs one thread each, in sequence; the deck copies and results go to --work.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

import h5py

from results_file import set_reaction

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

BLOCK_CONTACT = "contact sts master=block_bottom slave=base_top mu=0.3"


def prepare(work):
    """Copies the decks and meshes the cases use into work/, keeping their relative paths."""
    for folder in ("meshes", os.path.join("input", "paper"),
                   os.path.join("input", "verification", "contact")):
        target = os.path.join(work, folder)
        if not os.path.isdir(target):
            shutil.copytree(os.path.join(SOURCE, folder), target)


def deck_text(case, options, hertz_m):
    if case == "block":
        path = os.path.join(SOURCE, "input", "verification", "contact", "augmented_block.deck")
        text = open(path).read()
        assert BLOCK_CONTACT in text, f"block: {BLOCK_CONTACT!r} not found"
        text = text.replace(BLOCK_CONTACT, f"{BLOCK_CONTACT} {options}", 1)
        return text, ("input", "verification", "contact"), "block_top", ("interface", 4e-3)
    if case == "6.1b":
        path = os.path.join(SOURCE, "input", "paper", "sliding_block_6_1b_exact.deck")
        text = open(path).read()
        text, count = re.subn(r"eps_n=\S+ eps_t=\S+", options, text)
        assert count == 1, "6.1(b): eps_n=... eps_t=... not found"
        return text, ("input", "paper"), "block_top", ("interface", 7e-3)
    if case == "hertz":
        path = os.path.join(SOURCE, "input", "verification", "contact", "hertz_elastic_sphere.deck")
        text = open(path).read()
        text, count = re.subn(r"eps_n=\S+", options, text)
        assert count == 1, "hertz: eps_n=... not found"
        text = re.sub(r"\bm=\d+", f"m={hertz_m}", text, count=1)
        text = "\n".join(line for line in text.splitlines() if not line.startswith("reference"))
        return text + "\n", ("input", "verification", "contact"), "indenter_top", ("hertz", 0.0096)
    raise SystemExit(f"unknown case {case}")


def with_newton_options(text, options):
    """The deck text with `options` appended to its newton line, or on a new one after solve."""
    if not options:
        return text
    text, count = re.subn(r"^(\s*newton\b.*)$", rf"\1 {options}", text, count=1,
                          flags=re.MULTILINE)
    if count == 0:
        text, count = re.subn(r"^solve\s*$", f"solve\n  newton {options}", text, count=1,
                              flags=re.MULTILINE)
    assert count == 1, "no solve block to add newton options to"
    return text


def measure(path, set_name, pair):
    with h5py.File(path, "r") as h5:
        summary = dict(h5["summary"].attrs)
        steps = sorted(h5["steps"].values(), key=lambda s: s.attrs["time"])
        press = next((s for s in steps if abs(s.attrs["time"] - 1) < 1e-12), None)
        deepest = 0.0
        for step in steps:
            contact = step["contact"][pair]
            gap, state = contact["gap"][...], contact["state"][...]
            if (state != 0).any():
                deepest = max(deepest, float(-gap[state != 0].min()))
        return {
            "steps": int(summary["steps"]),
            "iterations": int(summary["total_iterations"]),
            "discarded": int(summary["discarded_iterations"]),
            "line_search": int(summary["line_search_retries"]),
            "continuation": int(summary.get("continuation_retries", 0)),
            "cutbacks": int(summary["cutbacks"]),
            "outcome": summary["outcome"].decode() if isinstance(summary["outcome"], bytes)
            else str(summary["outcome"]),
            "press": abs(set_reaction(press, set_name)[1 if set_name == "block_top" else 2])
            if press is not None else float("nan"),
            "drag": abs(set_reaction(steps[-1], set_name)[0]) if steps else float("nan"),
            "end_time": float(steps[-1].attrs["time"]) if steps else 0.0,
            "deepest": deepest,
        }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--cases", default="block,6.1b")
    parser.add_argument("--scales", default="0.01,0.1,1,10,100,1000,10000")
    parser.add_argument("--enforcements", default="penalty,augmented")
    parser.add_argument("--hertz-m", type=int, default=6)
    parser.add_argument("--timeout", type=float, default=3600)
    parser.add_argument("--newton", default="", help="options added to the decks' newton line")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    prepare(args.work)
    stamp = time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())
    print(f"covcontact {os.path.abspath(args.covcontact)}, {stamp}, "
          f"load average {os.getloadavg()[0]:.1f}" +
          (f", newton options: {args.newton}" if args.newton else ""))
    for case in args.cases.split(","):
        print(f"\n### {case}\n")
        print("| scale | enforcement | outcome | Newton its (+discarded) | line-search / continuation "
              "retries | cut-backs (steps) | press force | drag force end | deepest penetration | "
              "CPU s |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for scale in args.scales.split(","):
            for enforcement in args.enforcements.split(","):
                options = f"enforcement={enforcement} eps_scale={scale}"
                text, folder, set_name, (pair, depth) = deck_text(case, options, args.hertz_m)
                text = with_newton_options(text, args.newton)
                tag = re.sub(r"[^A-Za-z0-9.]+", "_", args.newton).strip("_")
                name = f"{case.replace('.', '')}_{enforcement}_{scale}" + (f"_{tag}" if tag else "")
                deck = os.path.join(args.work, *folder, name + ".deck")
                with open(deck, "w") as stream:
                    stream.write(text)
                results = os.path.join(args.work, name + ".h5")
                if os.path.exists(results):
                    os.remove(results)
                start = os.times()
                try:
                    run = subprocess.run([args.covcontact, "run", "-q", deck, "-o", results,
                                          "--threads", "1"], capture_output=True, text=True,
                                         timeout=args.timeout)
                    code = run.returncode
                except subprocess.TimeoutExpired:
                    code = "timeout"
                end = os.times()
                cpu = (end.children_user + end.children_system) - \
                      (start.children_user + start.children_system)
                if not os.path.exists(results):
                    print(f"| {scale} | {enforcement} | exit {code}, no results "
                          f"| | | | | | | {cpu:.1f} |")
                    continue
                m = measure(results, set_name, pair)
                outcome = m["outcome"] if code == 0 else f"exit {code} at t = {m['end_time']:.4g}"
                print(f"| {scale} | {enforcement} | {outcome} "
                      f"| {m['iterations']} (+{m['discarded']}) "
                      f"| {m['line_search']} / {m['continuation']} "
                      f"| {m['cutbacks']} ({m['steps']}) "
                      f"| {m['press']:.6f} | {m['drag']:.5f} | {m['deepest']:.2e} | {cpu:.1f} |",
                      flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
