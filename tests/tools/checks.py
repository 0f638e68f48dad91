"""What the tool tests in this folder share: a failed check ends the test (exit 1) with its message,
a missing prerequisite skips it (exit 77, ctest's SKIP_RETURN_CODE)."""

import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check(condition, message):
    if not condition:
        fail(message)


def skip(reason):
    print("skipped: " + reason)
    sys.exit(77)
