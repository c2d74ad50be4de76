"""The lines `covcontact run` prints while it steps (src/app/progress.cpp), parsed once for every
test script:

    step K  t = T of END  N iterations  |R|/|R0| = ...                     (a converged step)
      step K attempt A iteration I  t = T  |R|/|R0| = ...  contact: C active, S changed state,
      G changed segment[  det SIGN][  Krylov: K iterations to TOL]     (--newton-log, one line;
                                                                        the sign after a direct
                                                                        factorization, the
                                                                        Krylov part for
                                                                        iterative solves)

Scripts in tests/regression/* import it after `sys.path.insert(0, SUPPORT)`, SUPPORT being
this folder (see `support_path`)."""

import re

# A converged step: step number, time, end time, Newton iterations.
STEP_LINE = re.compile(r"^step (\d+)\s+t = (\S+) of (\S+)\s+(\d+) iterations", re.M)
# One Newton iteration of --newton-log: step, attempt, iteration, active points, points that
# changed state, points that changed segment.
ITERATION_LINE = re.compile(r"^\s+step (\d+) attempt (\d+) iteration (\d+) .*contact: (\d+) "
                            r"active, (\d+) changed state, (\d+) changed segment"
                            r"(?:  det ([-+0]))?(?:  Krylov: \d+ iterations to \S+)?$", re.M)


def converged_steps(stdout):
    """{step: Newton iterations} of the converged-step lines, in the order printed."""
    return {int(m[1]): int(m[4]) for m in STEP_LINE.finditer(stdout)}


def converged_step(line):
    """(step, iterations) if `line` (surrounding blanks ignored) is a converged-step line."""
    m = STEP_LINE.match(line.strip())
    return (int(m[1]), int(m[4])) if m else None


def iteration_lines(stdout):
    """[(step, attempt, iteration, active, changed state, changed segment)] of --newton-log."""
    return [tuple(int(g) for g in m.groups()[:6]) for m in ITERATION_LINE.finditer(stdout)]


def determinant_signs(stdout):
    """{(step, attempt, iteration): "+", "-" or "0"} of the --newton-log lines that print the
    sign of the tangent's determinant (a direct solver's factorization)."""
    return {tuple(int(g) for g in m.groups()[:3]): m[7] for m in ITERATION_LINE.finditer(stdout)
            if m[7]}
