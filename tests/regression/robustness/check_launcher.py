"""The `covcontact` launcher (src/app/launcher.cpp): it puts a run's OpenMP settings into the
environment and executes covcontact-engine in its own place, so that the program starts once.

  --case environment: `run --threads 1` and `--threads 2` of the ironing die deck; while the
      run goes, its process is the engine (/proc/PID/exe), its environment has
      OMP_WAIT_POLICY=passive and OMP_THREAD_LIMIT=N, and --threads 1 means one OS thread
      besides the signal watcher (which sleeps in sigwait; checked to have used at most one
      clock tick of CPU); a user's own OMP_WAIT_POLICY is kept; OPENBLAS_CORETYPE is the
      core type of this CPU's instruction sets (/proc/cpuinfo), and a user's own is kept.
  --case missing_program: the launcher alone, without the engine beside it, says which file it
      could not start and exits 70 (an incomplete installation is an internal error).
  --case bench_driver: the benchmark driver (tests/regression/performance/covcontact_bench,
      which scripts/bench.py runs) re-executes itself with the same OpenMP settings and
      OPENBLAS_CORETYPE as the engine, so that benchmarks measure the program users run.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
import stress_script  # noqa: E402
from cpu_flags import cpu_flags  # noqa: E402

WATCH_SECONDS = 4.0  # the die deck's press takes longer: set-up, factorizations and solves seen


def fail(message):
    sys.exit(f"FAIL: {message}")


def environment_of(pid):
    with open(f"/proc/{pid}/environ", "rb") as f:
        entries = f.read().split(b"\0")
    return dict(e.decode().split("=", 1) for e in entries if b"=" in e)


# The engine's one thread that computes nothing: it sleeps in sigwait for SIGINT/SIGTERM
# (src/app/stop_signals.hpp, kWatcherThreadName).
SIGNAL_WATCHER = "cc-stop-signals"


def task_field(pid, task, name):
    try:
        with open(f"/proc/{pid}/task/{task}/{name}") as f:
            return f.read()
    except OSError:
        return ""  # the thread ended meanwhile


def thread_count(pid):
    """The process's threads that may compute: all but the signal watcher, which must not have
    used more than one clock tick of CPU (utime + stime, fields 14 and 15 of its stat). None
    until the watcher carries its name: main starts it first of all and names it just after, so
    until then the process has main and the unnamed watcher only (a loaded machine caught that
    moment in CI)."""
    count, watcher = 0, False
    for task in os.listdir(f"/proc/{pid}/task"):
        if task_field(pid, task, "comm").strip() != SIGNAL_WATCHER:
            count += 1
            continue
        watcher = True
        fields = task_field(pid, task, "stat").rsplit(")", 1)[-1].split()
        ticks = int(fields[11]) + int(fields[12]) if len(fields) > 12 else 0
        if ticks > 1:
            fail(f"the signal watcher thread used {ticks} clock ticks of CPU")
    return count if watcher else None


def start_on_die_deck(args, command, threads, extra_environment):
    """Starts `command` (the program and its subcommand) on the die deck with `threads` threads,
    in an environment without the run's OpenMP and BLAS settings but for extra_environment."""
    deck = os.path.join(args.scratch, "ironing_die.deck")
    open(deck, "w").write(stress_script.ironing_deck_text(args, "ironing_sts_mu03_wide.deck"))
    environment = {k: v for k, v in os.environ.items()
                   if not k.startswith("OMP_") and k != "OPENBLAS_CORETYPE"}
    environment.update(extra_environment)
    return subprocess.Popen(command + [deck, "--threads", str(threads), "-o",
                                       os.path.join(args.scratch, f"die_{threads}.h5")],
                            env=environment, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)


def watch(process, observe):
    """Calls observe(pid) every 5 ms for up to WATCH_SECONDS, until it returns True or the
    process ends or leaves /proc, then stops the process."""
    started = time.time()
    try:
        while time.time() - started < WATCH_SECONDS and process.poll() is None:
            try:
                if observe(process.pid):
                    break
            except (FileNotFoundError, ProcessLookupError):
                break
            time.sleep(0.005)
    finally:
        process.kill()
        process.wait()


def watch_run(args, threads, extra_environment):
    """Starts the die deck on `threads` threads, watches it for WATCH_SECONDS and stops it;
    returns (its environment as the engine saw it, the most OS threads it had)."""
    process = start_on_die_deck(args, [args.covcontact, "run"], threads, extra_environment)
    seen, most_threads = None, None

    def observe(pid):
        nonlocal seen, most_threads
        if os.readlink(f"/proc/{pid}/exe").endswith("/covcontact-engine"):
            seen = seen or environment_of(pid)
            count = thread_count(pid)
            if count is not None:
                most_threads = max(most_threads or 0, count)
        return False

    watch(process, observe)
    if seen is None:
        fail(f"--threads {threads}: the process never became covcontact-engine "
             f"(exit {process.returncode}): {process.stderr.read()[-2000:]}")
    if most_threads is None:
        fail(f"--threads {threads}: no thread named {SIGNAL_WATCHER} in {WATCH_SECONDS} s")
    return seen, most_threads


def expected_openblas_core():
    """The OpenBLAS core type for this CPU by its flags in /proc/cpuinfo (the program asks the
    CPU itself): AVX2 + FMA -> Haswell (with or without AVX-512), else none."""
    if {"avx2", "fma"} <= cpu_flags():
        return "Haswell"
    return None


def environment_case(args):
    expected_core = expected_openblas_core()
    for threads in (1, 2):
        seen, most = watch_run(args, threads, {})
        print(f"--threads {threads}: OMP_WAIT_POLICY={seen.get('OMP_WAIT_POLICY')} "
              f"OMP_THREAD_LIMIT={seen.get('OMP_THREAD_LIMIT')}, at most {most} OS threads")
        if seen.get("OMP_WAIT_POLICY") != "passive" or seen.get("OMP_THREAD_LIMIT") != str(threads):
            fail(f"--threads {threads}: the engine did not get the OpenMP settings")
        if most > threads:
            fail(f"--threads {threads}: the run had {most} OS threads")
        print(f"--threads {threads}: OPENBLAS_CORETYPE={seen.get('OPENBLAS_CORETYPE')} "
              f"(expected from /proc/cpuinfo: {expected_core})")
        if seen.get("OPENBLAS_CORETYPE") != expected_core:
            fail(f"--threads {threads}: the engine did not get the BLAS kernels of this CPU")
    seen, _ = watch_run(args, 1, {"OMP_WAIT_POLICY": "active"})
    if seen.get("OMP_WAIT_POLICY") != "active":
        fail("a user's OMP_WAIT_POLICY=active was overridden")
    print("a user's OMP_WAIT_POLICY=active is kept")
    seen, _ = watch_run(args, 1, {"OPENBLAS_CORETYPE": "Sandybridge"})
    if seen.get("OPENBLAS_CORETYPE") != "Sandybridge":
        fail("a user's OPENBLAS_CORETYPE=Sandybridge was overridden")
    print("a user's OPENBLAS_CORETYPE=Sandybridge is kept")


def bench_driver_case(args):
    process = start_on_die_deck(args, [args.bench], 2, {})
    # The driver starts without the settings and re-executes itself with them: the environment
    # to judge is the last one seen.
    seen = None

    def observe(pid):
        nonlocal seen
        seen = environment_of(pid)
        return "OMP_WAIT_POLICY" in seen

    watch(process, observe)
    if seen is None:
        fail(f"the driver did not run (exit {process.returncode}): {process.stderr.read()[-2000:]}")
    expected_core = expected_openblas_core()
    print(f"driver: OMP_WAIT_POLICY={seen.get('OMP_WAIT_POLICY')} "
          f"OMP_THREAD_LIMIT={seen.get('OMP_THREAD_LIMIT')} "
          f"OPENBLAS_CORETYPE={seen.get('OPENBLAS_CORETYPE')} (expected {expected_core})")
    if seen.get("OMP_WAIT_POLICY") != "passive" or seen.get("OMP_THREAD_LIMIT") != "2":
        fail("the benchmark driver did not get the engine's OpenMP settings")
    if seen.get("OPENBLAS_CORETYPE") != expected_core:
        fail("the benchmark driver did not get the engine's BLAS kernels")


def missing_program_case(args):
    alone = os.path.join(args.scratch, "covcontact")
    shutil.copy(args.covcontact, alone)
    r = subprocess.run([alone, "run", "deck.deck"], capture_output=True, text=True, timeout=60)
    expected = f"cannot start the program {os.path.join(args.scratch, 'covcontact-engine')}"
    print(f"exit {r.returncode}: {r.stderr.strip()}")
    if r.returncode != 70 or expected not in r.stderr:
        fail(f"expected exit 70 and '{expected}'")


def main():
    cases = {"environment": environment_case, "missing_program": missing_program_case,
             "bench_driver": bench_driver_case}
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--covcontact", required=True)
    parser.add_argument("--bench", help="covcontact_bench (case bench_driver)")
    parser.add_argument("--decks", required=True, help="input/stress")
    parser.add_argument("--scratch", required=True, help="working directory (emptied first)")
    parser.add_argument("--case", required=True, choices=sorted(cases))
    args = parser.parse_args()
    shutil.rmtree(args.scratch, ignore_errors=True)
    os.makedirs(args.scratch)
    cases[args.case](args)


if __name__ == "__main__":
    main()
