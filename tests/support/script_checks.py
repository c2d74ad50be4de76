"""How a test script reports a failed check: `FAIL <message>` on stdout and exit code 1, which
CTest shows and counts as the test's failure. One writer for the scripts in tests/regression/*,
which import it after `sys.path.insert(0, SUPPORT)` as they import progress_lines."""
import sys


def fail(message):
    print("FAIL " + message)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)
