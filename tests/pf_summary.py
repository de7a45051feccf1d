#!/usr/bin/env python3
"""One line after `make test`: which framework ran the .pf unit tests, and how many.

    pf_summary.py BUILD_DIR

Reads BUILD_DIR/test_framework.txt (written at configure time) and the runners' own closing
lines in BUILD_DIR/Testing/Temporary/LastTest.log: pFUnit's "OK (N tests)" or "Tests run: N,
Failures: F, Errors: E" per executable, the translator's "Tests run: N, Failures: F" per
@test. Prints nothing else; exits 0 (ctest's status is the verdict).
"""
import os
import re
import sys


def main(argv):
    build = argv[1] if len(argv) > 1 else "build/debug"
    try:
        framework = open(os.path.join(build, "test_framework.txt")).read().strip()
        log = open(os.path.join(build, "Testing", "Temporary", "LastTest.log"),
                   errors="replace").read()
    except OSError as e:
        print(f"pf_summary: {e}")
        return 0
    runs = fails = errors = runners = 0
    for n in re.findall(r"^\s*\((\d+) tests?\b", log, re.M):        # pFUnit, all passed
        runs, runners = runs + int(n), runners + 1
    for n, f, e in re.findall(r"Tests run: (\d+), Failures: (\d+), Errors: (\d+)", log):
        runs, fails, errors, runners = runs + int(n), fails + int(f), errors + int(e), runners + 1
    print(f"unit tests (.pf) under {framework}: {runs} tests run by {runners} runner "
          f"executions, {fails} failures, {errors} errors")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
