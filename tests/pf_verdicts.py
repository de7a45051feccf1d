#!/usr/bin/env python3
"""Check that a .pf test executable gives pFUnit 4.14's verdicts (tests/pf_semantics/).

    pf_verdicts.py EXE FILE.pf {pfunit|translator}

FILE.pf names its tests pass_* (must pass) and fail_* (must fail). EXE, built from FILE.pf
by the named framework, is run once with all its tests. Required: it ends by an exit, not a
signal (a SIGFPE is not a verdict); every @test of FILE.pf ran; exactly the fail_* tests
failed; and the exit status is non-zero exactly when some test failed (the runner's own
"Encountered 1 or more failures" contract). Prints one line per test and a closing count.
"""
import re
import subprocess
import sys


def tests_in(pf):
    names, pending = [], False
    for line in open(pf, encoding="utf-8"):
        if re.match(r"\s*@test\s*$", line, re.IGNORECASE):
            pending = True
            continue
        m = re.match(r"\s*subroutine\s+(\w+)", line, re.IGNORECASE)
        if m and pending:
            names.append(m.group(1).lower())
            pending = False
    return names


def outcome(framework, text):
    """(ran, failed): sets of test names as the runner reports them."""
    if framework == "pfunit":   # --verbose: "Start: <suite.name>", "Failure in <suite.name>"
        ran = {m.lower() for m in re.findall(r"Start: <\w+?_suite\.(\w+)>", text)}
        failed = {m.lower() for m in re.findall(r"(?:Failure|Error) in <\w+?_suite\.(\w+)>", text)}
    else:                       # pf2f90 driver: "passed: name" / "FAILED: name"
        ran = {m.lower() for m in re.findall(r"^(?:passed|FAILED): (\w+)", text, re.M)}
        failed = {m.lower() for m in re.findall(r"^FAILED: (\w+)", text, re.M)}
    return ran, failed


def main(argv):
    if len(argv) != 4 or argv[3] not in ("pfunit", "translator"):
        print(__doc__, file=sys.stderr)
        return 2
    exe, pf, framework = argv[1:]
    args = [exe, "--verbose"] if framework == "pfunit" else [exe]
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       timeout=120)
    text = p.stdout
    problems, matched = [], 0
    if p.returncode < 0:
        problems.append(f"the runner was killed by signal {-p.returncode}")
    expected = tests_in(pf)
    ran, failed = outcome(framework, text)
    for name in expected:
        want = "fail" if name.startswith("fail_") else "pass"
        got = "not run" if name not in ran else ("fail" if name in failed else "pass")
        print(f"{framework}: {name}: expected {want}, got {got}")
        if got != want:
            problems.append(f"{name}: expected {want}, got {got}")
        else:
            matched += 1
    if set(ran) - set(expected):
        problems.append(f"unexpected tests ran: {sorted(set(ran) - set(expected))}")
    if (p.returncode != 0) != bool(failed):
        problems.append(f"exit status {p.returncode} with {len(failed)} failing test(s)")
    if failed and "Encountered 1 or more failures/errors during testing" not in text:
        problems.append("no 'Encountered 1 or more failures' line after failures")
    if problems:
        print(text)
        for what in problems:
            print("PROBLEM:", what)
    print(f"{matched} passed, {len(problems)} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
