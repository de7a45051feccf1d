#!/usr/bin/env python3
"""The translator refuses what pFUnit 4.14 cannot take (tests/pf_semantics/pfrefuse_*.pf).

    pf_refusals.py PF2F90 SEMANTICS_DIR WORK_DIR [FUNITPROC COMMAND... | -]

For each pfrefuse_*.pf: pf2f90.py must exit 1 with one line `pf2f90: PATH:LINE: ...` naming
the line the file's first comment gives ("(line N)" or "line (N)"), and write nothing. The
real .pf suite must still translate. With pFUnit's funitproc given, its output for the same
file must show why pFUnit fails there: a line over 132 columns, or the directive left
untranslated (a line that still starts with '@').
"""
import glob
import os
import re
import subprocess
import sys


def main(argv):
    if len(argv) < 5:
        print(__doc__, file=sys.stderr)
        return 2
    pf2f90, folder, work = argv[1], argv[2], argv[3]
    funitproc = [] if argv[4:] == ["-"] else argv[4:]
    os.makedirs(work, exist_ok=True)
    checks = problems = 0
    cases = sorted(glob.glob(os.path.join(folder, "pfrefuse_*.pf")))
    if len(cases) < 4:
        print(f"PROBLEM: expected at least 4 pfrefuse_*.pf in {folder}")
        return 1
    for pf in cases:
        head = open(pf, encoding="utf-8").read()
        line = re.search(r"line \(?(\d+)\)?", head).group(1)
        out = os.path.join(work, os.path.basename(pf)[:-3])
        p = subprocess.run([sys.executable, pf2f90, pf, "--out-dir", out],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        err = p.stderr.strip().splitlines()
        ok = (p.returncode == 1 and len(err) == 1 and err[0].startswith(f"pf2f90: {pf}:{line}: ")
              and not os.path.exists(out))
        checks += 1
        problems += not ok
        print(f"translator refuses {os.path.basename(pf)}: {'ok' if ok else 'NO'}: "
              f"exit {p.returncode}, {p.stderr.strip()}")
        if funitproc:
            target = os.path.join(work, os.path.basename(pf)[:-3] + ".F90")
            q = subprocess.run(funitproc + [pf, target], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
            text = open(target).read() if os.path.exists(target) else ""
            widest = max((len(t) for t in text.splitlines()
                          if not t.startswith("#")), default=0)
            stuck = [t for t in text.splitlines() if t.lstrip().startswith("@")]
            why = (f"funitproc exit {q.returncode}" if q.returncode else
                   f"a {widest}-column line" if widest > 132 else
                   f"untranslated: {stuck[0].strip()}" if stuck else "")
            checks += 1
            problems += not why
            print(f"  pFUnit cannot take it either: {'ok, ' + why if why else 'NO (it translates)'}")
    # the project's own suite must still pass through
    for pf in sorted(glob.glob(os.path.join(folder, "..", "test_*.pf"))):
        p = subprocess.run([sys.executable, pf2f90, pf, "--list"], stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
        checks += 1
        if p.returncode != 0:
            problems += 1
            print(f"PROBLEM: {pf} is refused: {p.stderr.strip()}")
    print(f"{checks - problems} passed, {problems} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
