"""The augmented Lagrangian's Uzawa updates under round-off (issue 16, part 3; nineteenth session
of issue 13): the soft block of test_augmented_lagrangian.cpp (eps_ref / 10, the penalty kept,
inexact re-solves) run once with each of OpenBLAS's x86 kernel sets this CPU can execute. The
kernels differ only in round-off. Before sliding points took the Laursen-Simo image
(contact_pair_augmentation.cpp), that decided the outcome: 5 steps with the Haswell kernels,
32 steps and 3 cut-backs ("100 augmentations did not reach aug_tol") with the SSE3 ones.

Asserted for every kernel set: the run completes its 5 steps without a cut-back, its Newton
iterations are within 25 % of the fewest, and its press and final drag forces agree with the
other kernel sets' within the two-decade bound of test_augmented_lagrangian.cpp (2 aug_tol times
the penalty's own press-force error at eps_ref; here 8.9e-5). A machine that is not x86 (the
variable is then ignored) runs the same deck once per entry, which must agree too.
"""
import argparse
import os
import re
import subprocess
import sys

import h5py

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from cpu_flags import cpu_flags  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "scripts"))
from results_file import set_reaction  # noqa: E402

CONTACT = "contact sts master=block_bottom slave=base_top mu=0.3"
NEWTON = "newton converge=residual residual=1e-10"
OPTIONS = "enforcement=augmented eps_scale=0.1 aug_grow=no"
NEWTON_OPTIONS = "aug_inner=0.1"
BOUND = 8.9e-5
ITERATION_SPREAD = 1.25


def fail(message):
    sys.exit(f"FAIL: {message}")


def kernel_sets():
    """OpenBLAS core types whose instructions this CPU has (a wrong one would be SIGILL)."""
    flags = cpu_flags()
    sets = ["Prescott"] if "sse3" in flags or "pni" in flags else ["default"]
    if "avx" in flags:
        sets.append("Sandybridge")
    if {"avx2", "fma"} <= flags:
        sets.append("Haswell")
    if {"avx512f", "avx512bw", "avx512vl"} <= flags:
        sets.append("SkylakeX")
    return sets


def run(covcontact, deck, scratch, kernels):
    env = dict(os.environ)
    if kernels != "default":
        env["OPENBLAS_CORETYPE"] = kernels
    output = os.path.join(scratch, f"soft_{kernels}.h5")
    done = subprocess.run([covcontact, "run", deck, "--output", output, "--threads", "1"],
                          env=env, capture_output=True, text=True, timeout=120)
    line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else ""
    print(f"{kernels}: {line}")
    if done.returncode != 0:
        fail(f"{kernels}: exit {done.returncode}\n{done.stdout}\n{done.stderr}")
    match = re.search(r"completed: (\d+) steps, (\d+) Newton iterations.*?(\d+) cut-backs", line)
    if not match:
        fail(f"{kernels}: no completion line in {line!r}")
    with h5py.File(output, "r") as h5:
        steps = sorted(h5["steps"].values(), key=lambda s: s.attrs["time"])
        press = abs(set_reaction(steps[0], "block_top")[1])
        drag = abs(set_reaction(steps[-1], "block_top")[0])
    return {"steps": int(match[1]), "iterations": int(match[2]), "cutbacks": int(match[3]),
            "press": press, "drag": drag}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--deck", required=True, help="input/verification/contact/augmented_block.deck")
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    os.makedirs(args.scratch, exist_ok=True)
    text = open(args.deck).read()
    for line, added in ((CONTACT, OPTIONS), (NEWTON, NEWTON_OPTIONS)):
        if line not in text:
            fail(f"{args.deck}: {line!r} not found")
        text = text.replace(line, f"{line} {added}", 1)
    # Beside the original, so that its relative mesh path holds; removed afterwards.
    deck = os.path.join(os.path.dirname(os.path.abspath(args.deck)),
                        f".soft_kernels_{os.getpid()}.deck")
    with open(deck, "w") as f:
        f.write(text)
    sets = kernel_sets()
    try:
        results = {k: run(args.covcontact, deck, args.scratch, k) for k in sets}
        if len(sets) == 1:  # not x86: the same run twice must agree as well
            results["again"] = run(args.covcontact, deck, args.scratch, sets[0])
    finally:
        os.remove(deck)
    fewest = min(r["iterations"] for r in results.values())
    first = next(iter(results.values()))
    for kernels, r in results.items():
        if r["steps"] != 5 or r["cutbacks"] != 0:
            fail(f"{kernels}: {r['steps']} steps with {r['cutbacks']} cut-backs, expected 5 and 0")
        if r["iterations"] > ITERATION_SPREAD * fewest:
            fail(f"{kernels}: {r['iterations']} Newton iterations against the fewest {fewest}")
        for name in ("press", "drag"):
            if abs(r[name] / first[name] - 1) > BOUND:
                fail(f"{kernels}: {name} force {r[name]:.7f} against {first[name]:.7f}")
    print("PASS:", ", ".join(f"{k} {r['iterations']} its" for k, r in results.items()))


if __name__ == "__main__":
    main()
