#!/usr/bin/env python3
"""The cluster scripts (scripts/slurm-*.sbatch) run as Slurm would run them, outside Slurm:
array tasks pick their deck line (comments and blank lines skipped), write their outputs
and return spallbar's exit status; the MPI sweep script writes the same table as a serial
sweep.

usage: cli_slurm_scripts.py SPALLBAR SCRIPTS_DIR INPUT_DIR WORK_DIR MPIEXEC|-
"""
import os
import shutil
import subprocess
import sys

from clitools import Checks

exe, scripts, indir, work, mpiexec = sys.argv[1:6]
check = Checks()
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
env = dict(os.environ, SPALLBAR=exe)
with open(os.path.join(work, "decks.txt"), "w") as f:
    f.write("# decks for the array\n\n")
    for name in ("example1", "suspended_static"):     # the second reads a relative table
        f.write(os.path.join(indir, name + ".nml") + "\n")
    f.write(os.path.join(work, "missing.nml") + "\n")
expect = {1: 0, 2: 0, 3: 2, 4: 2}
for task, status in expect.items():
    p = subprocess.run(["bash", os.path.join(scripts, "slurm-array.sbatch"), "decks.txt", "out"],
                       cwd=work, env=dict(env, SLURM_ARRAY_TASK_ID=str(task)),
                       capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    check(p.returncode == status, f"array task {task}: exit {p.returncode}, expected {status}: "
          f"{p.stderr.strip()}")
for name in ("example1", "suspended_static"):
    for ext in ("his", "prf", "evt", "frg"):
        check(os.path.isfile(os.path.join(work, "out", f"{name}.{ext}")), f"out/{name}.{ext}")

if mpiexec != "-":
    deck = open(os.path.join(indir, "sweeps", "weibull_spall.nml")).read()
    deck = deck.replace("realizations = 32", "realizations = 4")
    open(os.path.join(work, "sw.nml"), "w").write(deck)
    p = subprocess.run([exe, "--sweep", "sw.nml", "-o", "serial", "-q"], cwd=work,
                       capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    check(p.returncode == 0, f"serial sweep: {p.stderr}")
    p = subprocess.run(["bash", os.path.join(scripts, "slurm-sweep-mpi.sbatch"), "sw.nml", "mpi"],
                       cwd=work, env=dict(env, SLURM_NTASKS="2", MPIRUN=mpiexec),
                       capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
    check(p.returncode == 0, f"sweep script: exit {p.returncode}: {p.stderr.strip()[:300]}")
    rows = lambda f: [l for l in open(os.path.join(work, f)) if not l.startswith("#")]
    check(os.path.isfile(os.path.join(work, "mpi.sweep")) and rows("mpi.sweep") == rows("serial.sweep"),
          "the sweep script's table equals the serial sweep's")
sys.exit(check.finish())
