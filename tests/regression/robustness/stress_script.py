"""Shared by the issue-14 scripts of this folder (check_newton_diagnostics.py,
check_quadratic_tail.py, check_ironing_edge.py, check_step_start_sliding.py,
check_nts_patch_edges.py, check_ball_cap_edge.py, ...): their command line (--covcontact,
--decks input/stress, --scratch), the exact-tangent copy of the large-slip deck they run, the
ironing and ball decks with absolute paths, and a run of such a deck's first steps."""
import argparse
import os
import re
import subprocess
import sys


def parse_args():
    parser = argparse.ArgumentParser()
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--decks", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    os.makedirs(args.scratch, exist_ok=True)
    return args


def exact_large_slip_deck(args):
    """input/stress/large_slip_step.deck with tangent=exact, written to the scratch folder with
    its mesh path made absolute; returns the copy's path."""
    source = open(os.path.join(args.decks, "large_slip_step.deck")).read()
    deck = os.path.join(args.scratch, "large_slip_step_exact.deck")
    mesh = os.path.abspath(os.path.join(args.decks, "../../meshes/block_on_base.geo"))
    open(deck, "w").write(source.replace("../../meshes/block_on_base.geo", mesh)
                          .replace("name=interface", "name=interface tangent=exact"))
    return deck


def ironing_deck_text(args, name, folder="ironing"):
    """The text of input/stress/FOLDER/NAME (the ironing decks, or the ball decks with
    folder="ball") with its include and mesh paths made absolute, so that a variant of it can be
    written to the scratch folder."""
    here = os.path.abspath(os.path.join(args.decks, folder))
    source = open(os.path.join(here, name)).read()
    meshes = os.path.abspath(os.path.join(args.decks, "../../meshes"))
    source = re.sub(r'^include "([^"/]+)"', lambda m: f'include "{os.path.join(here, m.group(1))}"',
                    source, flags=re.M)
    return source.replace('"../../../meshes/', '"' + meshes + "/")


def run_ironing_steps(args, name, steps, must_contain=(), folder="ironing", may_fail=False,
                      newton="", label="", timeout=280):
    """Runs input/stress/FOLDER/NAME (100 steps of dt = 0.01) cut to its first `steps` steps,
    one thread, with --newton-log, in the scratch folder; checks that the deck says each of
    `must_contain`, exits with the run's output if it fails (unless `may_fail`: a script that
    checks a failure itself), and returns the CompletedProcess. `newton` (e.g.
    "line_search=yes") adds a `newton` line to the solution control; `label` tells such a
    variant's files apart (<deck>_<steps><label>.h5, ..._reactions.csv). `timeout` (seconds)
    only guards against a hang: the test's own ctest TIMEOUT must exceed it."""
    source = ironing_deck_text(args, name, folder)
    for text in ("steps 100 dt=0.01",) + tuple(must_contain):
        assert text in source, f"{name} no longer says {text!r}"
    if newton:
        source = re.sub(r"^solve(.*)$", rf"solve\1\n  newton {newton}", source, count=1,
                        flags=re.M)
    stem = f"{os.path.splitext(name)[0]}_{steps}{label}"
    deck = os.path.join(args.scratch, stem + ".deck")
    open(deck, "w").write(source.replace("steps 100 dt=0.01", f"steps {steps} dt=0.01"))
    r = subprocess.run([args.covcontact, "run", "--threads", "1", "--newton-log", deck, "-o",
                        os.path.join(args.scratch, stem + ".h5")],
                       capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0 and not may_fail:
        sys.exit(f"the run failed: exit {r.returncode}\n{r.stdout[-3000:]}{r.stderr[-2000:]}")
    return r


def developed_sliding_failures(r, steps, allow_line_search_retries=False):
    """What a run of run_ironing_steps() did against issue 14's targets: no cut-back (with
    allow_line_search_retries, a retry of a step with the line search at the same step size is
    not one), all `steps` steps completed, and at most 4 Newton iterations per developed step
    (t > 0.4, 100 steps of dt = 0.01). Returns the failures and the mean iterations per
    developed step (None if the log has the wrong number of developed steps)."""
    failures = []
    retry = "retrying the step with line search"
    cutbacks = [line for line in (r.stdout + r.stderr).splitlines()
                if line.startswith("cut-back at")
                and not (allow_line_search_retries and retry in line)]
    if cutbacks:
        failures.append("cut-backs:\n" + "\n".join(cutbacks))
    if f"completed: {steps} steps" not in r.stdout:
        failures.append(f"the run did not complete {steps} steps:\n" + r.stdout[-2000:])
    developed = [int(line.split()[7]) for line in r.stdout.splitlines()
                 if line.startswith("step ") and float(line.split()[4]) > 0.4 + 1e-9]
    if len(developed) != steps - 40:
        failures.append(f"{len(developed)} developed steps in the log, expected {steps - 40}")
        return failures, None
    mean = sum(developed) / len(developed)
    if mean > 4:
        failures.append(f"{mean:.2f} Newton iterations per developed step (target <= 4)")
    return failures, mean
