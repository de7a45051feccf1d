#!/usr/bin/env python3
"""cmake --install (issue 21): spallbar, spallbar-compare, the plot scripts, the example decks
and the man page land under the prefix, and the installed program runs an installed example
from any folder (paths in a deck are relative to the deck) and says how it was built.

usage: cli_install.py BUILD_DIR WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

from clitools import Checks, run


def main():
    build, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    prefix = os.path.join(work, "inst")
    r = subprocess.run(["cmake", "--install", build, "--prefix", prefix], capture_output=True,
                       text=True)
    check(r.returncode == 0, f"cmake --install: exit {r.returncode} {r.stderr[-500:]}")
    for f in ("bin/spallbar", "bin/spallbar-compare", "share/man/man1/spallbar.1",
              "share/spallbar/plots/xt.py", "share/spallbar/plots/spbread.py",
              "share/spallbar/examples/example1.nml", "share/spallbar/examples/example1_wave.txt",
              "share/spallbar/examples/example3_case2/accelerate_above_h19.nml"):
        check(os.path.isfile(os.path.join(prefix, f)), f"not installed: {f}")
    for f in ("bin/spallbar", "bin/spallbar-compare", "share/spallbar/slurm/slurm-array.sbatch",
              "share/spallbar/slurm/slurm-sweep-mpi.sbatch",
              "share/spallbar/slurm/slurm-restart.sbatch"):
        check(os.access(os.path.join(prefix, f), os.X_OK), f"not installed or not executable: {f}")
    # the examples are decks and their tables only, whatever ran beside them in input/
    ex = os.path.join(prefix, "share", "spallbar", "examples")
    other = [os.path.join(d, f) for d, _, fs in os.walk(ex) for f in fs
             if not f.endswith((".nml", ".txt"))]
    check(not other, f"installed beside the example decks: {other[:5]}")
    exe = os.path.join(prefix, "bin", "spallbar")
    r = run(exe, ["--version"], work)
    lines = r.stdout.splitlines()
    opts = lines[3].split() if len(lines) > 3 else []
    check(len(opts) == len(set(opts)), f"--version: an option repeated: {lines[3:4]}")
    # the identity (version and the sources' digest, doc/build.md) and where they came from
    check(r.returncode == 0 and len(lines) == 6 and
          re.fullmatch(r"spallbar \d+\.\d+\.\d+ \(source [0-9a-f]{12}\)", lines[0]) and
          lines[1].startswith("  sources:  ") and
          lines[2].startswith("  compiler: ") and lines[4].startswith("  sweeps: ") and
          lines[5].startswith("  HDF5: "), f"--version: {r.stdout!r}")
    print("ok   installed --version: " + " | ".join(l.strip() for l in lines))
    deck = os.path.join(prefix, "share", "spallbar", "examples", "example1.nml")
    r = run(exe, [deck, "--output", "ex1", "--quiet"], work)
    check(r.returncode == 0, f"installed example1 from another folder: exit {r.returncode} "
          f"{r.stderr}")
    r2 = run(exe, [deck, "--output", "ex1b", "--quiet"], work)
    cmp = subprocess.run([os.path.join(prefix, "bin", "spallbar-compare"), "ex1.his", "ex1b.his",
                          "--quiet"], cwd=work, capture_output=True, text=True)
    check(r2.returncode == 0 and cmp.returncode == 0,
          f"installed spallbar-compare: exit {cmp.returncode} {cmp.stderr}")
    print("ok   the installed program runs an installed example from another folder; "
          "the installed spallbar-compare passes it against itself")
    man = subprocess.run(["man", "-l", os.path.join(prefix, "share/man/man1/spallbar.1")],
                         capture_output=True, text=True, env=dict(os.environ, MANPAGER="cat",
                                                                  PAGER="cat"))
    if man.returncode == 0 and man.stdout:
        check("EXIT STATUS" in man.stdout, "man page: no EXIT STATUS section")
        print("ok   man -l spallbar.1 renders")
    else:
        print("skip man page rendering: no man here")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
