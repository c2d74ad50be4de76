#!/usr/bin/python3
"""Runs on several processes (issue 17): `mpirun -np N covcontact run DECK` against the serial run.

--case crossing: decks/block_crossing_partition.deck (a block split by the partition dragged
  along a base, with cut-backs and an inverted element on the way) on 2 processes: the serial
  run's step times and iteration counts exactly, forces and displacements to 1e-8, the serial
  run's per-iteration contact counts (--newton-log: in contact, changed state, changed segment),
  the serial run's determinant signs wherever both runs print one (--newton-log: UMFPACK or
  CHOLMOD against MUMPS), at least one contact point whose master segment moved to another
  process, and one results file written by both processes (parallel HDF5) with the serial
  file's layout and XDMF.
--case restart: input/stress/restart_6_1.deck on 2 processes stopped by SIGTERM (sent to the
  processes, as a scheduler does) after step 8: exit 4 as in a serial run, every reported step
  in the file; continued with --restart on 1 and on 3 processes, every remaining step as the
  uninterrupted serial run (iterations exactly, forces to 1e-8).
--case predictor: the crossing deck with `predictor=extrapolate` (issue 14) on 2 processes: the
  serial run's steps, iterations and forces (the prediction and its reference norms are formed
  from the process-summed tangent products), and a restart on 2 processes from step 8 of that
  file (its restart data carry the step's increment) continues as the uninterrupted serial run.
--case stabilize: the crossing deck with viscous stabilisation (`newton stabilize=1e-3`, then
  `stabilize_share=0.01`, whose factor each process chooses from the replicated state, then
  `maxit=4 stabilize_on_failure=1e-3`, whose retries and cut-backs every process must decide
  alike) on 2 processes: the serial run's steps, iterations and forces, and its energy account
  with the stabilisation's work (each process adds the viscous forces of the elements it owns).
--case facets: the faceted ironing die (input/stress/ironing/ironing_sts_mu03_wide.deck, 30
  steps) with `predictor=extrapolate line_search=yes` on 2 processes: the serial run's steps,
  iterations and forces. Its line search measures trials over facet edges against the attempt's
  largest residual (newton.hpp), a decision from crossing counts summed over the processes; in
  these steps it is taken 4 times (steps 23 and 24).
--case damped: the ironing press at mu = 0.6 (input/stress/ironing/ironing_nts_mu06_wide.deck,
  4 steps), whose step 4 is damped by the line search within its plain attempt: 2 processes
  take the serial run's steps, iterations and forces, and neither run fails an attempt.
--case repeat: decks/repeatable_amg.deck (20 k equations) three times on 2 processes with
  GMRES + BoomerAMG: the same Krylov and Newton iterations and residual history, bit for bit,
  and the same displacements (users compare iteration counts between runs).
--case inexact: input/performance/scaling_20k.deck on 2 processes with GMRES + BoomerAMG and
  with MUMPS: Newton iterations per step with the inexact solves at most one more than with the
  direct solver's (issue 13), and the contact force of the last step equal to 1e-6.
--case setup: input/performance/scaling_11k.deck on 2 processes with GMRES + GAMG whose level
  smoothers are SOR (PETSC_OPTIONS): with PETSc 3.18 every set-up of that preconditioner fails
  there (SUBPC_ERROR) on a regular tangent. Each iteration must then be solved by MUMPS and say
  so, and the run must be the MUMPS run's: the same steps and iterations, forces and
  displacements to 1e-8 (before, the failure was taken for a singular tangent and the run stopped
  after its cut-backs with exit 7).
--case directmiss: the crossing deck with every MUMPS solve counted as missed
  (PETSC_OPTIONS=-cc_direct_residual 1e-30, as a nearly singular tangent leaves a direct solve):
  on one process UMFPACK solves each such iteration, says so, and the run is the UMFPACK run
  (steps, iterations, forces to 1e-8); on 2 processes the run ends as a singular one (exit 7,
  the reason named), where the second miss used to leave it as an internal error.
--case errors: `check` on 2 processes prints the serial output once; a deck error on 2
  processes exits with the serial exit code and is reported once; a persistent inverted element (input/stress/inverted_element_persistent.deck) exits
  with the serial code, keeps the same converged steps and names the element once; a singular
  tangent (the thin strip loaded before it touches) is diagnosed as serially; SIGKILL of
  one process ends every process (no hang) and leaves every reported step readable.

Usage: check_mpi_runs.py --covcontact BIN --mpirun MPIRUN --source DIR --scratch DIR --case C
"""
import argparse
import fcntl
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import progress_lines  # noqa: E402  (tests/support)
from script_checks import check  # noqa: E402  (tests/support)

TIMEOUT_S = 240  # one command on a loaded 2-core machine
TOLERANCE = 1e-8  # serial against distributed: different summation order and solver only
STRIP_TOLERANCE = 1e-6  # stabilized_strip: solves at 2.7e-7 of the right-hand side
EXIT = {"ok": 0, "usage": 1, "input": 2, "interrupted": 4}  # `covcontact --help`


def mpirun(args, processes):
    # Root in CI containers; more processes than cores for -np 3 on 2 cores.
    return [args.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(processes)]


def covcontact(args, processes, *words):
    prefix = mpirun(args, processes) if processes > 1 else []
    return prefix + [args.covcontact, *words]


def run(args, processes, *words, env=None):
    """`covcontact WORDS` on `processes` processes in the scratch folder; `env` replaces the
    environment (PETSC_OPTIONS)."""
    return subprocess.run(covcontact(args, processes, *words), cwd=args.scratch,
                          capture_output=True, text=True, timeout=TIMEOUT_S, env=env)


def run_ok(args, processes, *words, raw=False):
    """`run`, which must succeed. raw: standard output and error as the bytes the run wrote,
    decoded without translating newlines (text mode reads a carriage return as a line end)."""
    if raw:
        result = subprocess.run(covcontact(args, processes, *words), cwd=args.scratch,
                                capture_output=True, timeout=TIMEOUT_S)
        result.stdout, result.stderr = result.stdout.decode(), result.stderr.decode()
    else:
        result = run(args, processes, *words)
    check(result.returncode == EXIT["ok"],
          f"{' '.join(result.args)}: exit {result.returncode}\n{result.stdout}\n{result.stderr}")
    return result


def step_names(h5):
    return sorted(h5["steps"].keys(), key=lambda name: int(h5["steps"][name].attrs["step"]))


def compare_steps(reference_path, results_path, first_step=1, pair="interface"):
    """Steps >= first_step of a results file against the reference (the contact force of the
    named pair among the fields); returns (steps, worst)."""
    with h5py.File(reference_path, "r") as reference, h5py.File(results_path, "r") as results:
        names = step_names(results)
        expected = [name for name in step_names(reference)
                    if int(reference["steps"][name].attrs["step"]) >= first_step]
        check(names == expected, f"{results_path}: steps {names[:3]}..., expected {expected[:3]}...")
        worst = 0.0
        for name in names:
            a, b = reference["steps"][name], results["steps"][name]
            for attribute in ("time", "iterations", "cutbacks"):
                check(a.attrs[attribute] == b.attrs[attribute],
                      f"{results_path} step {name}: {attribute} {b.attrs[attribute]}, serial "
                      f"{a.attrs[attribute]}")
            for field in ("set_reactions", f"contact/{pair}/total_force", "displacement"):
                want, got = a[field][...], b[field][...]
                error = np.abs(got - want).max() / max(np.abs(want).max(), 1e-300)
                worst = max(worst, error)
                check(error <= TOLERANCE, f"{results_path} step {name}: {field} differs by {error:.2e}")
        check(results["summary"].attrs["outcome"] == "completed", f"{results_path}: not completed")
    return len(names), worst


ENERGIES = ("external_work", "strain_energy", "contact_energy", "dissipation")


def compare_energy(reference_path, results_path, quantities=ENERGIES):
    """The energy account of every step (attributes every process writes alike) against the
    serial run's, each quantity to 1e-8 of its largest magnitude over the run."""
    with h5py.File(reference_path, "r") as reference, h5py.File(results_path, "r") as results:
        names = step_names(reference)
        for quantity in quantities:
            want = np.array([reference["steps"][n]["energy"].attrs[quantity] for n in names])
            got = np.array([results["steps"][n]["energy"].attrs[quantity] for n in names])
            scale = max(np.abs(want).max(), 1e-300)
            error = np.abs(got - want).max() / scale
            check(error <= TOLERANCE, f"{results_path}: energy {quantity} differs by {error:.2e}")
            check(scale > 1e-300 or quantity == "dissipation", f"energy {quantity} is zero")
    print(f"energy account of {len(names)} steps as serial ({', '.join(quantities)})")


def layout_of(path):
    """Every object of a results file: path -> (kind, shape, dtype, sorted attribute names)."""
    objects = {}

    def visit(name, item):
        shape = getattr(item, "shape", None)
        dtype = str(getattr(item, "dtype", ""))
        objects[name] = (type(item).__name__, shape, dtype, sorted(item.attrs.keys()))

    with h5py.File(path, "r") as h5:
        h5.visititems(visit)
        root = sorted(h5.attrs.keys()), int(h5.attrs["writing_processes"])
    return objects, root


def same_layout(serial, distributed):
    """The file the processes wrote together has the serial file's layout object by object."""
    (serial_objects, (serial_root, serial_writers)), (objects, (root, writers)) = (
        layout_of(serial), layout_of(distributed))
    check(serial_writers == 1 and writers == 2,
          f"writing_processes: serial {serial_writers}, 2 processes {writers}")
    check(root == serial_root, f"root attributes {root}, serial {serial_root}")
    differ = [name for name in sorted(set(serial_objects) | set(objects))
              if serial_objects.get(name) != objects.get(name)]
    check(not differ, f"{len(differ)} objects differ from the serial file's, e.g. "
          f"{[(n, serial_objects.get(n), objects.get(n)) for n in differ[:3]]}")
    # Rank 0 writes the sidecars: the XDMF as serial (but for the file name it points to), the
    # CSV with the serial header and one row per written step.
    with open(serial[:-3] + ".xdmf") as a, open(distributed[:-3] + ".xdmf") as b:
        expected = a.read().replace(os.path.basename(serial), os.path.basename(distributed))
        check(b.read() == expected, "the XDMF sidecar differs from the serial run's")
    with open(serial[:-3] + "_reactions.csv") as a, open(distributed[:-3] + "_reactions.csv") as b:
        want, got = a.read().splitlines(), b.read().splitlines()
        check(len(got) == len(want) and got[0] == want[0],
              f"CSV sidecar: {len(got)} lines, header {got[:1]}; serial {len(want)}, {want[:1]}")
    print(f"one file written by 2 processes: {len(objects)} objects, the serial layout; "
          f"XDMF and CSV sidecars as serial")


def crossing_case(args):
    deck = os.path.join(args.source, "tests/regression/parallel/decks/block_crossing_partition.deck")
    serial = os.path.join(args.scratch, "serial.h5")
    distributed = os.path.join(args.scratch, "two.h5")
    serial_run = run_ok(args, 1, "run", deck, "-o", serial, "--newton-log")
    result = run_ok(args, 2, "run", deck, "-o", distributed, "--newton-log", raw=True)
    count, worst = compare_steps(serial, distributed)
    # Each process evaluates only its own contact points in the iterations: the per-iteration
    # counts of points in contact and of state and segment changes are summed over processes
    # and must be the serial run's, iteration by iteration.
    serial_log, distributed_log = (progress_lines.iteration_lines(r.stdout)
                                   for r in (serial_run, result))
    check(len(serial_log) > count, f"serial run printed {len(serial_log)} iteration lines")
    check(distributed_log == serial_log,
          f"--newton-log contact counts differ from the serial run's:\n{distributed_log[:20]}\n"
          f"serial:\n{serial_log[:20]}")
    # The sign of each tangent's determinant, from the serial run's own factorizations (UMFPACK,
    # CHOLMOD; none where a factor was reused) and from the distributed MUMPS factorizations
    # (every iteration): the same wherever both tell, a negative one included (the deck's
    # failed attempt through an inverted element). The fold verdict of a failing step on
    # several processes rests on these (solver/tangent_orientation.hpp).
    serial_signs, distributed_signs = (progress_lines.determinant_signs(r.stdout)
                                       for r in (serial_run, result))
    check(len(distributed_signs) == len(distributed_log),
          f"2 processes printed the determinant's sign at {len(distributed_signs)} of "
          f"{len(distributed_log)} iterations")
    common = sorted(set(serial_signs) & set(distributed_signs))
    check(len(common) >= 10 and "-" in (serial_signs[k] for k in common),
          f"only {len(common)} iterations with a sign in both runs, or none negative")
    differ = [k for k in common if serial_signs[k] != distributed_signs[k]]
    check(not differ, f"determinant signs differ at (step, attempt, iteration) {differ}")
    # Open MPI gives each rank a pseudo-terminal for its output even when mpirun's goes to a
    # pipe or a file: the run must still print plain lines, one per converged step, as serially
    # (a live line's carriage returns ran the step lines of `mpirun ... > log` together; the
    # output is read raw, since text mode would turn them into line ends).
    check("\r" not in result.stdout, "2 processes printed carriage returns (a live line)")
    check(progress_lines.converged_steps(result.stdout)
          == progress_lines.converged_steps(serial_run.stdout),
          f"converged-step lines differ from the serial run's:\n{result.stdout[:2000]}")
    same_layout(serial, distributed)
    compare_energy(serial, distributed)
    moved = [line for line in result.stdout.splitlines()
             if line.startswith("contact points whose master segment moved")]
    check(len(moved) == 1, f"no line on master segments changing process:\n{result.stdout}")
    crossings = int(moved[0].split(":")[1].split()[0])
    check(crossings > 0, "no contact point slid onto another process's master segments")
    print(f"2 processes: {count} steps as serial (largest difference {worst:.1e}); "
          f"{crossings} point-steps onto another process's master segments")


def refusal_case(args, option, refusal):
    """A run on 2 processes of the crossing deck with `option` on its contact line refuses it:
    exit 2, the deck's file:line, `refusal` said once; the serial run completes."""
    source = os.path.join(args.source, "tests/regression/parallel/decks")
    with open(os.path.join(source, "block_crossing_partition.deck")) as stream:
        text = stream.read()
    mesh = "../../../../meshes/block_on_base.geo"
    check(mesh in text and "name=interface" in text, "the crossing deck changed")
    deck = os.path.join(args.scratch, "refused.deck")
    with open(deck, "w") as stream:
        stream.write(text.replace(mesh, os.path.normpath(os.path.join(source, mesh)))
                     .replace("name=interface", f"{option} name=interface"))
    line = 1 + text.splitlines().index(next(l for l in text.splitlines() if "name=interface" in l))
    run_ok(args, 1, "run", deck, "-o", os.path.join(args.scratch, "serial.h5"))
    result = run(args, 2, "run", deck, "-o", os.path.join(args.scratch, "two.h5"))
    check(result.returncode == EXIT["input"],
          f"2 processes: exit {result.returncode}, expected {EXIT['input']}\n{result.stderr}")
    where = f"{deck}:{line}"
    check(result.stderr.count(refusal) == 1 and where in result.stderr,
          f"2 processes: the refusal is not said once with {where}:\n{result.stderr}")
    print(f"2 processes refuse {option} at {where}; 1 process completes")


def augmented_case(args):
    """enforcement=augmented with Anderson's acceleration (aug_depth 5, the default) on several
    processes. Until the nineteenth session sliding points kept the augmentation of their last
    sticking update, the points where the block turns from stick to slip flipped at every
    update, and round-off decided which: on the small block at eps_ref / 10 one and two processes
    took 5 and 17 steps, and runs on several processes refused the option. With Lambda_T <- T at
    sliding points (contact_pair_augmentation.cpp):
    - the crossing deck at eps_ref / 10, with full and with inexact re-solves (aug_inner=0.1),
      gives the serial run's steps, Newton iterations and forces (to TOLERANCE) on 2 processes;
    - the small block at eps_ref / 10 (aug_grow=no), the former 5 against 17 steps, takes the
      serial run's steps with its Newton iterations in each. Its results are compared to the
      criterion only: 363 Newton solves, each stopped at 1e-10 of its first residual, leave the
      serial run itself determined to about 1e-7, and the 2-process run lies 6e-8 from it."""
    edit = ("eps_n=2.1e6 eps_t=2.1e6 mu=0.3", "mu=0.3 enforcement=augmented eps_scale=0.1")
    for name, newton in (("full", "aug_inner=0"), ("inexact", "aug_inner=0.1")):
        deck = crossing_variant(args, f"crossing_augmented_{name}", newton, edit)
        serial = os.path.join(args.scratch, f"{name}_serial.h5")
        distributed = os.path.join(args.scratch, f"{name}_two.h5")
        run_ok(args, 1, "run", deck, "-o", serial, "-q")
        run_ok(args, 2, "run", deck, "-o", distributed, "-q")
        count, worst = compare_steps(serial, distributed)
        print(f"augmented crossing deck ({name} re-solves) on 2 processes: {count} steps as "
              f"serial (largest difference {worst:.1e})")
    block = os.path.join(args.source, "input/verification/contact/augmented_block.deck")
    text = open(block).read()
    contact = "contact sts master=block_bottom slave=base_top mu=0.3"
    check(contact in text and '"../../../meshes/' in text, "the augmented block deck changed")
    text = text.replace(contact, f"{contact} enforcement=augmented eps_scale=0.1 aug_grow=no")
    text = text.replace('"../../../meshes/', '"' + os.path.join(args.source, "meshes") + "/")
    deck = os.path.join(args.scratch, "augmented_block.deck")
    open(deck, "w").write(text)
    counts = []
    for processes in (1, 2):
        output = os.path.join(args.scratch, f"block_{processes}.h5")
        run_ok(args, processes, "run", deck, "-o", output, "-q")
        with h5py.File(output, "r") as h5:
            check(h5["summary"].attrs["outcome"] == "completed", f"{output}: not completed")
            counts.append([(int(step.attrs["step"]), int(step.attrs["iterations"]),
                            int(step.attrs["cutbacks"])) for step in h5["steps"].values()])
    check(counts[1] == counts[0],
          f"the block on 2 processes: (step, iterations, cut-backs) {counts[1]}, serial {counts[0]}")
    print(f"augmented block at eps_ref / 10 on 2 processes: the serial run's {len(counts[0])} "
          f"steps and {sum(c[1] for c in counts[0])} Newton iterations")


def segments_case(args):
    """integration=segments (issue 16, part 1) rebuilds its points every step with decisions that
    jump where master and slave edges align; on the crossing deck, round-off differences between
    1 and 2 processes changed the number of points (114 against 108 in step 3) and the iteration
    counts. Until that is fixed a run on several processes refuses the option."""
    refusal_case(args, "integration=segments",
                 "integration=segments is not available on several processes")


def rank_processes(launcher):
    """The covcontact processes mpirun started (its children)."""
    listed = subprocess.run(["pgrep", "-P", str(launcher.pid)], capture_output=True, text=True)
    return [int(pid) for pid in listed.stdout.split()]


def signal_after_step(args, processes, deck, results, after_step, signal_number, only_rank=None):
    """Starts a distributed run and signals its processes (all, or one) once rank 0 reports
    `after_step`; returns (exit code, highest reported step, output)."""
    launcher = subprocess.Popen(covcontact(args, processes, "run", deck, "-o", results),
                                cwd=args.scratch, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
    reported, output = 0, []
    for line in launcher.stdout:
        output.append(line)
        # Rank 0's output reaches mpirun through a terminal, so progress comes as \r-separated
        # updates; "step k/n  t = ..  m iterations" says step k converged (and is written).
        for update in line.split("\r"):
            converged = progress_lines.converged_step(update)
            if converged:
                reported = max(reported, converged[0])
        if reported >= after_step:
            ranks = sorted(rank_processes(launcher))
            check(len(ranks) == processes, f"found {len(ranks)} processes under mpirun")
            for pid in ranks if only_rank is None else [ranks[only_rank]]:
                os.kill(pid, signal_number)
            break
    output += launcher.stdout.readlines()
    launcher.wait(timeout=TIMEOUT_S)
    return launcher.returncode, reported, "".join(output)


def restart_case(args):
    deck = os.path.join(args.source, "input/stress/restart_6_1.deck")
    reference = os.path.join(args.scratch, "uninterrupted.h5")
    interrupted = os.path.join(args.scratch, "interrupted.h5")
    run_ok(args, 1, "run", deck, "-o", reference, "-q")
    code, reported, output = signal_after_step(args, 2, deck, interrupted, 8, signal.SIGTERM)
    check(code == EXIT["interrupted"], f"SIGTERM on 2 processes: exit {code}\n{output}")
    with h5py.File(interrupted, "r") as h5:
        stored = [int(h5["steps"][name].attrs["step"]) for name in step_names(h5)]
        check(h5["summary"].attrs["outcome"] == "interrupted", "outcome is not 'interrupted'")
    check(stored == list(range(1, len(stored) + 1)) and len(stored) >= reported,
          f"stored steps {stored}, reported {reported}")
    print(f"2 processes stopped by SIGTERM after step {stored[-1]}: exit 4, steps 1..{stored[-1]} kept")
    for processes in (1, 3):
        continued = os.path.join(args.scratch, f"continued_{processes}.h5")
        run_ok(args, processes, "run", deck, "-o", continued, "--restart", interrupted, "-q")
        count, worst = compare_steps(reference, continued, stored[-1] + 1)
        print(f"  continued on {processes} process(es): {count} steps as the uninterrupted serial "
              f"run (largest difference {worst:.1e})")


def crossing_variant(args, name, newton_options, contact_edit=None):
    """A copy of the crossing deck in the scratch folder with `newton_options` on a newton line
    after `solve` and its contact line edited by contact_edit = (old, new); returns its path."""
    source = os.path.join(args.source, "tests/regression/parallel/decks/block_crossing_partition.deck")
    text = open(source).read()
    check("\nsolve\n" in text, "the crossing deck changed")
    here = os.path.dirname(source)
    text = re.sub(r'^(include|mesh)(\s+)"([^"/][^"]*)"',
                  lambda m: f'{m[1]}{m[2]}"{os.path.normpath(os.path.join(here, m[3]))}"', text,
                  flags=re.M)
    if contact_edit:
        check(contact_edit[0] in text, "the crossing deck's contact line changed")
        text = text.replace(*contact_edit)
    deck = os.path.join(args.scratch, name + ".deck")
    open(deck, "w").write(text.replace("\nsolve\n", f"\nsolve\n  newton {newton_options}\n"))
    return deck


def serial_and_two(args, deck, pair="interface"):
    """Runs the deck on 1 and on 2 processes and compares their steps; returns both results
    files and compare_steps' (steps, worst)."""
    serial = os.path.join(args.scratch, "serial.h5")
    distributed = os.path.join(args.scratch, "two.h5")
    run_ok(args, 1, "run", deck, "-o", serial, "-q")
    run_ok(args, 2, "run", deck, "-o", distributed, "-q")
    return serial, distributed, *compare_steps(serial, distributed, pair=pair)


def predictor_case(args):
    deck = crossing_variant(args, "crossing_predictor", "predictor=extrapolate")
    serial, distributed, count, worst = serial_and_two(args, deck)
    continued = os.path.join(args.scratch, "continued.h5")
    run_ok(args, 2, "run", deck, "-o", continued, "--restart", distributed, "--from-step", "8",
           "-q")
    rest, rest_worst = compare_steps(serial, continued, 9)
    print(f"predictor=extrapolate on 2 processes: {count} steps as serial (largest difference "
          f"{worst:.1e}); restarted from step 8 on 2: {rest} steps as serial ({rest_worst:.1e})")


def stabilize_case(args):
    # maxit=4 makes steps fail without stabilisation, so that stabilize_on_failure retries them,
    # cuts them back stabilised and lets later steps go without it: every process must take
    # the same decisions (the steps' iterations and cut-backs are compared).
    for option in ("stabilize=1e-3", "stabilize_share=0.01",
                   "maxit=4 stabilize_on_failure=1e-3"):
        deck = crossing_variant(args, "crossing_stabilize", option)
        serial, distributed, count, worst = serial_and_two(args, deck)
        compare_energy(serial, distributed, ENERGIES + ("stabilization_dissipation",))
        if "on_failure" in option:
            with h5py.File(serial, "r") as one, h5py.File(distributed, "r") as two:
                retries = [int(f["summary"].attrs["stabilized_retries"]) for f in (one, two)]
            check(retries[0] > 0 and retries[0] == retries[1],
                  f"{option}: steps retried with stabilisation {retries} (serial, 2 processes)")
        with h5py.File(serial, "r") as h5:
            energy = h5["steps"][step_names(h5)[-1]]["energy"].attrs
            share = energy["stabilization_dissipation"] / energy["external_work"]
        check(share > 1e-6,
              f"{option}: the stabilisation did no work worth checking ({share:.1e} of the work)")
        print(f"{option} on 2 processes: {count} steps as serial (largest difference "
              f"{worst:.1e}); the stabilisation took {100 * share:.2g} % of the work")
    stabilized_strip(args)


def loaded_strip_deck(args, name, newton_options=None):
    """The thin strip of input/stress/thin_shell_on_cylinder.deck loaded at its end before it
    touches the cylinder (the variant of SingularSystem.ThinStrip*), in the scratch folder, with
    `newton_options` on a newton line after `solve`; returns its path."""
    source = os.path.join(args.source, "input/stress")
    with open(os.path.join(source, "thin_shell_on_cylinder.deck")) as f:
        strip = f.read()
    for old in ('mesh "thin_strip.geo"', "fix end_bottom uz", ' uz "t"', "\nsolve\n"):
        check(old in strip, f"thin_shell_on_cylinder.deck changed: no {old!r}")
    strip = strip.replace('mesh "thin_strip.geo"',
                          f'mesh "{os.path.join(source, "thin_strip.geo")}"', 1)
    strip = strip.replace("fix end_bottom uz", 'load end fz "-t" total', 1)
    strip = strip.replace(' uz "t"', "", 1)
    if newton_options:
        strip = strip.replace("\nsolve\n", f"\nsolve\n  newton {newton_options}\n", 1)
    deck = os.path.join(args.scratch, name + ".deck")
    with open(deck, "w") as f:
        f.write(strip)
    return deck


def stabilized_strip(args):
    """The loaded strip carried by stabilize_on_failure_share on 1 and 2 processes. Its
    stabilised tangents are nearly singular: MUMPS's solves leave 2.7e-7 of the right-hand side,
    at a normwise backward error of 1e-16 (the round-off of the tangent's conditioning), and
    before that was accepted the 2 processes stopped as singular at step 3. Same steps,
    iterations, cut-backs and stabilised retries as serially; displacements and the contact
    force to STRIP_TOLERANCE, which allows for solves only that exact (measured: 2.5e-9 and
    2.7e-8). The supports' reactions, about 1e-6 of the load and set by the converged residual,
    are not compared."""
    deck = loaded_strip_deck(args, "strip_stabilized", "stabilize_on_failure_share=0.01")
    results = [os.path.join(args.scratch, f"strip_stabilized{n}.h5") for n in (1, 2)]
    for processes, path in zip((1, 2), results):
        run_ok(args, processes, "run", deck, "-o", path, "-q")
    worst = 0.0
    with h5py.File(results[0], "r") as one, h5py.File(results[1], "r") as two:
        names = step_names(one)
        check(step_names(two) == names and len(names) >= 10,
              f"stabilised strip: steps {step_names(two)} on 2 processes, serial {names}")
        for attribute in ("stabilized_retries", "total_iterations", "cutbacks",
                          "discarded_iterations"):
            values = [f["summary"].attrs[attribute] for f in (one, two)]
            check(values[0] == values[1] and (attribute != "stabilized_retries" or values[0] > 0),
                  f"stabilised strip: {attribute} {values} (serial, 2 processes)")
        for name in names:
            a, b = one["steps"][name], two["steps"][name]
            check(a.attrs["iterations"] == b.attrs["iterations"],
                  f"stabilised strip step {name}: iterations differ")
            for field in ("displacement", "contact/roller/total_force"):
                want, got = a[field][...], b[field][...]
                scale = max(np.abs(want).max(), 1e-300)
                if field != "displacement" and scale < 1e-12:
                    continue  # no contact yet
                error = np.abs(got - want).max() / scale
                worst = max(worst, error)
                check(error <= STRIP_TOLERANCE,
                      f"stabilised strip step {name}: {field} differs by {error:.2e}")
    print(f"stabilize_on_failure_share on the loaded strip: {len(names)} steps on 2 processes "
          f"as serially (largest difference {worst:.1e})")


def ironing_variant(args, name, steps, newton=""):
    """input/stress/ironing/NAME.deck in the scratch directory with its 100 steps cut to `steps`
    and, if given, a `newton` line added to its solve block."""
    here = os.path.join(args.source, "input/stress/ironing")
    text = open(os.path.join(here, name + ".deck")).read()
    check("\nsolve\n" in text and "steps 100 dt=0.01" in text, f"the deck {name} changed")
    text = re.sub(r'^(include|mesh)(\s+)"([^"/][^"]*)"',
                  lambda m: f'{m[1]}{m[2]}"{os.path.normpath(os.path.join(here, m[3]))}"', text,
                  flags=re.M)
    if newton:
        text = text.replace("\nsolve\n", f"\nsolve\n  newton {newton}\n")
    deck = os.path.join(args.scratch, name + ".deck")
    open(deck, "w").write(text.replace("steps 100 dt=0.01", f"steps {steps} dt=0.01"))
    return deck


def facets_case(args):
    deck = ironing_variant(args, "ironing_sts_mu03_wide", 30,
                           "predictor=extrapolate line_search=yes")
    serial, distributed, count, worst = serial_and_two(args, deck, pair="die")
    check(count == 30, f"{count} steps compared, expected 30")
    print(f"the faceted die with the line search on 2 processes: {count} steps as serial "
          f"(largest difference {worst:.1e})")


def damped_case(args):
    # Step 4 of this press stagnates near convergence and is damped by the line search within
    # its plain attempt (newton_stall.hpp): the decision and every line-search fraction come
    # from norms summed over the processes, so 2 processes take the serial run's iterations.
    deck = ironing_variant(args, "ironing_nts_mu06_wide", 4)
    serial, distributed, count, worst = serial_and_two(args, deck, pair="die")
    check(count == 4, f"{count} steps compared, expected 4")
    for path in (serial, distributed):
        with h5py.File(path, "r") as h5:
            summary = h5["summary"].attrs
            check(summary["line_search_retries"] == 0 and summary["discarded_iterations"] == 0,
                  f"{path}: an attempt failed (the press is no longer damped in its attempt)")
            check(int(h5["steps"][step_names(h5)[-1]].attrs["iterations"]) > 9,
                  f"{path}: step 4 converged before the stagnation test could fire")
    print(f"the damped press on 2 processes: {count} steps as serial (largest difference "
          f"{worst:.1e})")


def repeat_case(args):
    deck = os.path.join(args.source, "tests/regression/parallel/decks/repeatable_amg.deck")
    histories, krylov = [], []
    for attempt in range(3):
        results = os.path.join(args.scratch, f"run{attempt}.h5")
        result = run_ok(args, 2, "run", deck, "-o", results, "--solver", "amg", "--cost", "-q")
        costs = [line for line in result.stdout.splitlines() if line.startswith("cost: ")]
        check(len(costs) == 1, f"no cost line:\n{result.stdout}")
        krylov.append(re.search(r'"krylov_iterations": *(\d+)', costs[0])[1])
        with h5py.File(results, "r") as h5:
            check(h5["summary"].attrs["outcome"] == "completed", f"{results}: not completed")
            history = h5["convergence"][...]
            last = step_names(h5)[-1]
            histories.append((history, h5["steps"][last]["displacement"][...]))
    (first, displacement), *others = histories
    for attempt, (history, other_displacement) in enumerate(others, 2):
        check(len(history) == len(first),
              f"run {attempt}: {len(history)} Newton iterations, run 1: {len(first)}")
        for column in ("step", "iteration", "residual", "relative_energy"):
            check(np.array_equal(history[column], first[column]),
                  f"run {attempt}: {column} differs from run 1's")
        check(np.array_equal(other_displacement, displacement),
              f"run {attempt}: displacements differ from run 1's")
    check(len(set(krylov)) == 1, f"Krylov iterations differ between runs: {krylov}")
    print(f"3 runs on 2 processes: {len(first)} Newton iterations and {krylov[0]} Krylov "
          f"iterations each, residual histories and displacements equal bit for bit")


def steps_of(path):
    """Newton iterations per step and the last step's contact force of a results file."""
    with h5py.File(path, "r") as h5:
        check(h5["summary"].attrs["outcome"] == "completed", f"{path}: not completed")
        names = step_names(h5)
        counts = [int(h5["steps"][name].attrs["iterations"]) for name in names]
        return counts, h5["steps"][names[-1]]["contact/interface/total_force"][...]


def inexact_case(args):
    deck = os.path.join(args.source, "input/performance/scaling_20k.deck")
    runs = {}
    for solver in ("mumps", "amg"):
        results = os.path.join(args.scratch, f"{solver}.h5")
        run_ok(args, 2, "run", deck, "-o", results, "--solver", solver, "-q")
        runs[solver] = steps_of(results)
    (direct, direct_force), (inexact, inexact_force) = runs["mumps"], runs["amg"]
    check(len(direct) == len(inexact), f"steps: MUMPS {direct}, BoomerAMG {inexact}")
    check(all(i <= d + 1 for i, d in zip(inexact, direct)),
          f"Newton iterations per step: BoomerAMG {inexact}, MUMPS {direct} (at most +1 each)")
    error = np.abs(inexact_force - direct_force).max() / np.abs(direct_force).max()
    check(error <= 1e-6, f"last step's contact force differs by {error:.2e}")
    print(f"Newton iterations per step: BoomerAMG {inexact}, MUMPS {direct}; contact force "
          f"equal to {error:.1e}")


def setup_case(args):
    deck = os.path.join(args.source, "input/performance/scaling_11k.deck")
    direct = os.path.join(args.scratch, "mumps.h5")
    run_ok(args, 2, "run", deck, "-o", direct, "--solver", "mumps", "-q")
    failing = os.path.join(args.scratch, "gamg_sor.h5")
    environment = dict(os.environ, PETSC_OPTIONS="-cc_gamg_mg_levels_ksp_type richardson "
                                                 "-cc_gamg_mg_levels_pc_type sor")
    result = run(args, 2, "run", deck, "-o", failing, "--solver", "gamg", "-q", env=environment)
    check(result.returncode == EXIT["ok"], f"GAMG with SOR: exit {result.returncode}\n"
                                           f"{result.stdout}\n{result.stderr}")
    failed = [line for line in result.stderr.splitlines()
              if "GMRES+GAMG: factorization failed" in line]
    check(failed, "GAMG with SOR smoothers no longer fails its set-up here: this case tests "
                  f"nothing, find another trigger\n{result.stderr}")
    check(all(line.endswith("; solving this iteration with MUMPS") for line in failed),
          f"a failed set-up without the fallback's note: {failed[0]}")
    count, worst = compare_steps(direct, failing)
    print(f"GAMG's set-up failed in {len(failed)} iterations, each solved by MUMPS: {count} steps "
          f"as the MUMPS run (largest difference {worst:.1e})")


def direct_miss_case(args):
    deck = os.path.join(args.source, "tests/regression/parallel/decks/block_crossing_partition.deck")
    # Below round-off, every MUMPS solve counts as missed (its residual far above round-off, as
    # a nearly singular tangent leaves it).
    # A backward-stable solve is accepted at its round-off, which -cc_direct_backward_error 0
    # rules out.
    environment = dict(os.environ,
                       PETSC_OPTIONS="-cc_direct_residual 1e-30 -cc_direct_backward_error 0")
    reference = os.path.join(args.scratch, "umfpack.h5")
    run_ok(args, 1, "run", deck, "-o", reference, "--solver", "umfpack", "-q")
    missed = os.path.join(args.scratch, "mumps_missed.h5")
    serial = run(args, 1, "run", deck, "-o", missed, "--solver", "mumps", "-q", env=environment)
    check(serial.returncode == EXIT["ok"], f"one process, every MUMPS solve missed: exit "
                                           f"{serial.returncode}\n{serial.stderr}")
    notes = [line for line in serial.stderr.splitlines() if "relative residual" in line]
    check(notes and all(line.endswith("; solving this iteration with UMFPACK") for line in notes),
          f"a missed MUMPS solve without UMFPACK's note: {notes[:1]}")
    count, worst = compare_steps(reference, missed)
    # Several processes have no other direct solver: the iteration fails as a singular system,
    # and the run ends as a singular one does, with its message, not as an internal error.
    distributed = run(args, 2, "run", deck, "-o", os.path.join(args.scratch, "two.h5"), "-q",
                      env=environment)
    output = distributed.stdout + distributed.stderr
    check(distributed.returncode == 7 and "internal error" not in output,
          f"2 processes, every MUMPS solve missed: exit {distributed.returncode}, expected 7 "
          f"(singular)\n{output[-2000:]}")
    check("the tangent is numerically singular for the direct solver" in output,
          f"2 processes: the message does not say why\n{output[-2000:]}")
    print(f"one process: {len(notes)} missed MUMPS solves taken by UMFPACK, {count} steps as the "
          f"UMFPACK run (largest difference {worst:.1e}); 2 processes: exit 7 with the reason")


def wait_until_unlocked(path, seconds=60):
    """Waits until no process holds the writer's lock on `path`. A process being ended still
    holds its files for a moment after its command line has gone from /proc (the kernel frees
    its memory first): with ASan's terabytes of mappings that moment lasted long enough for the
    reader to meet the lock (h5py: 'unable to lock file')."""
    deadline = time.monotonic() + seconds
    with open(path, "rb") as stream:
        while True:
            try:
                fcntl.flock(stream, fcntl.LOCK_SH | fcntl.LOCK_NB)
                fcntl.flock(stream, fcntl.LOCK_UN)
                return
            except BlockingIOError:
                check(time.monotonic() < deadline, f"{path} still locked {seconds} s after the run")
                time.sleep(0.05)


def errors_case(args):
    good = os.path.join(args.source, "tests/regression/paper/decks/6_1b_short_full.deck")
    serial, two = run(args, 1, "check", good), run(args, 2, "check", good)
    check(serial.returncode == 0 and two.returncode == 0 and two.stdout == serial.stdout,
          f"check on 2 processes printed\n{two.stdout}\nserial\n{serial.stdout}")
    print("check on 2 processes: the serial output, once")

    bad = os.path.join(args.source, "tests/decks/bad/unknown_keyword.deck")
    serial, two = run(args, 1, "run", bad, "-o", "bad1.h5"), run(args, 2, "run", bad, "-o", "bad2.h5")
    check(serial.returncode == EXIT["input"] and two.returncode == serial.returncode,
          f"deck error: exit {two.returncode} on 2 processes, {serial.returncode} serial")
    message = serial.stderr.strip().splitlines()[0]
    check((two.stdout + two.stderr).count(message) == 1,
          f"the deck error is not reported exactly once:\n{two.stdout}{two.stderr}")
    print(f"deck error: exit {two.returncode} on 2 processes, reported once: {message}")

    # solve-dump solves on one process: under mpirun its PETSc solver waited for the processes
    # that had left (a hang); it now refuses before it reads the directory.
    dump = run(args, 2, "solve-dump", args.scratch, "--solver", "amg")
    check(dump.returncode == EXIT["usage"] and "one process" in dump.stderr,
          f"solve-dump on 2 processes: exit {dump.returncode}\n{dump.stderr}")
    print("solve-dump on 2 processes: refused (exit 1) instead of waiting")

    deck = os.path.join(args.source, "input/stress/inverted_element_persistent.deck")
    serial = run(args, 1, "run", deck, "-o", "inverted1.h5")
    two = run(args, 2, "run", deck, "-o", "inverted2.h5")
    check(serial.returncode != 0 and two.returncode == serial.returncode,
          f"inverted element: exit {two.returncode} on 2 processes, {serial.returncode} serial")
    with h5py.File(os.path.join(args.scratch, "inverted1.h5"), "r") as a, \
            h5py.File(os.path.join(args.scratch, "inverted2.h5"), "r") as b:
        check(step_names(a) == step_names(b) and len(step_names(a)) >= 1,
              f"kept steps {step_names(b)}, serial {step_names(a)}")
    final = [line for line in serial.stderr.splitlines() if line.startswith("covcontact: run")]
    check(len(final) == 1 and (two.stdout + two.stderr).count(final[0]) == 1,
          f"the failure is not reported once:\n{two.stderr}")
    print(f"inverted element: exit {two.returncode} as serial, same kept steps, reported once")

    # The thin strip loaded at its end before it touches the cylinder (the variant of
    # SingularSystem.ThinStrip*): a singular tangent, whose diagnosis applies the rigid-body
    # motions to the tangent. Each process holds a share of it; the products are summed over
    # the processes, so 2 processes name the serial run's free motion. Before, each process
    # judged its own share, and the run named a translation along x and a rotation about y too,
    # which the strip's symmetry support holds.
    deck = loaded_strip_deck(args, "strip_singular")
    serial = run(args, 1, "run", deck, "-o", "strip1.h5")
    two = run(args, 2, "run", deck, "-o", "strip2.h5")
    free = "unconstrained rigid-body motion: translation along z of body 'strip';"
    check(serial.returncode == 7 and two.returncode == serial.returncode,
          f"singular strip: exit {two.returncode} on 2 processes, {serial.returncode} serial")
    check(free in serial.stderr and free in two.stderr,
          f"singular strip: the diagnosis differs\nserial: {serial.stderr[-1500:]}\n"
          f"2 processes: {two.stderr[-1500:]}")
    print(f"singular strip: exit 7 on 1 and 2 processes, both naming only the free motion: {free}")

    deck = os.path.join(args.source, "input/stress/restart_6_1.deck")
    killed = os.path.join(args.scratch, "killed.h5")
    start = time.monotonic()
    code, reported, output = signal_after_step(args, 2, deck, killed, 5, signal.SIGKILL, only_rank=1)
    seconds = time.monotonic() - start
    check(code != 0, "the run survived the SIGKILL of a process")
    leftover = subprocess.run(["pgrep", "-f", killed], capture_output=True, text=True).stdout
    check(not leftover.strip(), f"processes left after the kill: {leftover}")
    wait_until_unlocked(killed)
    with h5py.File(killed, "r") as h5:
        stored = [int(h5["steps"][name].attrs["step"]) for name in step_names(h5)]
        for name in step_names(h5):
            check(np.all(np.isfinite(h5["steps"][name]["displacement"][...])), f"step {name} unreadable")
    check(stored == list(range(1, len(stored) + 1)) and len(stored) >= reported,
          f"after SIGKILL of rank 1: stored {stored}, reported {reported}")
    print(f"SIGKILL of rank 1 after step {reported}: every process ended (exit {code}, "
          f"{seconds:.1f} s), steps 1..{stored[-1]} readable")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--mpirun", required=True)
    parser.add_argument("--source", required=True, help="the source tree")
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--case", required=True,
                        choices=["crossing", "restart", "errors", "segments", "augmented",
                                 "predictor", "stabilize", "facets", "damped", "repeat",
                                 "inexact", "setup", "directmiss"])
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    {"crossing": crossing_case, "restart": restart_case, "errors": errors_case,
     "segments": segments_case, "augmented": augmented_case,
     "predictor": predictor_case, "stabilize": stabilize_case, "facets": facets_case,
     "damped": damped_case, "repeat": repeat_case,
     "inexact": inexact_case, "setup": setup_case,
     "directmiss": direct_miss_case}[args.case](args)


if __name__ == "__main__":
    main()
