#!/usr/bin/env python3
"""The cluster scripts (scripts/slurm-*.sbatch) run as Slurm would run them, outside Slurm:
array tasks pick their deck line (comments and blank lines skipped), write their outputs
and return spallbar's exit status; the MPI sweep script writes the same table as a serial
sweep; the restart script, stopped by SIGTERM (as Slurm does before the time limit) and
started again, ends with the outputs of one uninterrupted run; the MPI sweep script stopped
by SIGTERM exits 143 with the table written (mpirun itself exits 1).

usage: cli_slurm_scripts.py SPALLBAR SCRIPTS_DIR INPUT_DIR WORK_DIR MPIEXEC|-
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

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
    rows = lambda f: [l for l in open(os.path.join(work, f)) if l.startswith(" ")]
    check(os.path.isfile(os.path.join(work, "mpi.sweep")) and rows("mpi.sweep") == rows("serial.sweep"),
          "the sweep script's table equals the serial sweep's")
    # the sweep script stopped by SIGTERM (as --signal=B:TERM@60 does): it passes the signal
    # to mpirun once; the ranks write the table (cases not run: status -1); mpirun exits 1,
    # the script 143
    # 900 cases of 100 ms of bar time: far longer than the 2.5 s before the signal (a case
    # of 1 ms takes about a millisecond in the Release build)
    open(os.path.join(work, "long.nml"), "w").write(
        deck.replace("realizations = 4", "realizations = 300").replace("t_end = 1.0e-3",
                                                                       "t_end = 1.0e-1"))
    proc = subprocess.Popen(["bash", os.path.join(scripts, "slurm-sweep-mpi.sbatch"), "long.nml",
                             "stopped"], cwd=work, stdin=subprocess.DEVNULL,
                            env=dict(env, SLURM_NTASKS="2", MPIRUN=mpiexec,
                                     OMPI_MCA_odls_base_sigkill_timeout="2"),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.5)
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=120)
    check(proc.returncode == 143, f"sweep script stopped by SIGTERM: exit {proc.returncode} "
          f"({out.strip()[-300:]} {err.strip()[:300]})")
    check("stopped by signal 15 (mpirun exit 1)" in out, f"sweep script says so: {out.strip()}")
    st = [l.split()[8] for l in rows("stopped.sweep")]
    check(len(st) == 900 and "-1" in st and "0" in st,
          f"sweep script stopped: 900 rows, some done, some not run (status -1)")
# the restart script: SIGTERM to the script, then the script again
deck = open(os.path.join(indir, "example3_case2", "min_fragment_h190.nml")).read()
deck = re.sub(r"(&run\n)", "\\1  checkpoint = 'long.ck.h5'\n  checkpoint_every = 500\n", deck,
              count=1)
os.makedirs(os.path.join(work, "long"))
open(os.path.join(work, "long", "long.nml"), "w").write(deck)
p = subprocess.run([exe, "long.nml", "-o", "U", "-q"], cwd=os.path.join(work, "long"),
                   capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
check(p.returncode == 0, f"long deck, uninterrupted: {p.stderr.strip()}")
os.remove(os.path.join(work, "long", "long.ck.h5"))
script = os.path.join(scripts, "slurm-restart.sbatch")
proc = subprocess.Popen(["bash", script, "long/long.nml", "long/R"], cwd=work, env=env,
                        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                        stderr=subprocess.PIPE, text=True)
deadline = time.time() + 120
while (not os.path.exists(os.path.join(work, "long", "long.ck.h5")) and proc.poll() is None
       and time.time() < deadline):
    time.sleep(0.005)
proc.send_signal(signal.SIGTERM)
out, err = proc.communicate(timeout=300)
check(proc.returncode == 143, f"restart script stopped by SIGTERM: exit {proc.returncode} "
      f"({err.strip()[:300]})")
check("run this script again" in out, f"restart script says how to go on: {out.strip()}")
p = subprocess.run(["bash", script, "long/long.nml", "long/R"], cwd=work, env=env,
                   capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL)
check(p.returncode == 0, f"restart script, second job: exit {p.returncode} "
      f"({p.stderr.strip()[:300]})")
check("going on from long.ck.h5" in p.stdout, f"second job restarts: {p.stdout.strip()}")
for ext in ("his", "prf", "evt", "frg"):
    a = open(os.path.join(work, "long", "U." + ext), "rb").read()
    b = open(os.path.join(work, "long", "R." + ext), "rb").read()
    check(a == b, f"restart script: R.{ext} equals the uninterrupted U.{ext}")
p = subprocess.run(["bash", script, os.path.join(indir, "example1.nml"), "e1"], cwd=work,
                   env=env, capture_output=True, text=True, timeout=300,
                   stdin=subprocess.DEVNULL)
check(p.returncode == 2 and "sets no &run checkpoint" in p.stderr,
      f"restart script without a checkpoint in the deck: exit 2 ({p.stderr.strip()})")
sys.exit(check.finish())
