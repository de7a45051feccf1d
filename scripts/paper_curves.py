#!/usr/bin/env python3
"""The paper's figures as archival data (issue 20): the curves of Figs. 7c and 10 where the
paper gives them in closed form, kept in archive/paper/ as a digitised curve would be, and the
program's curves compared with them by spallbar-compare.

    paper_curves.py --exe SPALLBAR [--compare SPALLBAR_COMPARE] --work DIR
                    [--plots DIR] [--report FILE] [--write-archive]

* Fig. 7c, Example 1 (the one-cell splinter at the free end of a suspended bar): the
  paper's closed forms V^n = [2 s_1 - d_1 + (n - 2.5) dm g] dt/dm (translation) and
  V~^n = (-1)^n (d_1 + 0.5 dm g) dt/dm (vibration), n = 3 ... 40, with s_1 = 160 kPa,
  d_1 = 60 kPa, dm = 1.8e5 dt kg/m^2, dt = 5e-4 s, g = 9.81 (archive/paper/fig07c_example1.txt:
  n V V_vib). The program's V and V~ are the mean and the half difference of the splinter's
  two node velocities (the x-t fields of input/example1.nml), at the same n; compared at
  rtol 1e-9 (the method reproduces the closed form to round-off).
* Fig. 10, the bar fixed in the base (the paper's dashed curve; input/example3_case1_fixed.nml):
  in self-weight equilibrium at t = 0, loaded on its free top by p(t) = 0.1 (1 - t/0.5 s)^3
  MPa, the base reaction of the continuum is
      R(t) = rho g h + 2 sum_k (-1)^k p(t - (2k + 1) h/a)     (period 4 h/a while p is constant)
  sampled every 0.25 ms over [0, 1 s] (archive/paper/fig10_fixed_reaction.txt: t R). The
  program's reaction is the section stress at the half steps (3.1)-(3.2): row t^n holds
  t^(n-1/2) (between jumps it equals R(t^n - dt/2) to 0.04 Pa of 216 kPa: the stepwise load,
  the mean of p over two steps, differs from p by O(dt^2 p'')). A jump of R (every 2 h/a) is
  on the lattice's rows, up to one step late, and the first row after it stands for a time
  half a step after the jump, over which R changes by up to |dR/dt| dt/2 = 280 Pa (1.3e-3 of
  R). So the comparison is a tube of 1.25 steps (--time-tol 0.59 ms: one step and a margin
  for the abscissae's rounding) at rtol 2e-3.

--write-archive writes the two archive files from the closed forms (they are data: commit
them); without it the script checks. Exit 0 when both curves pass, 1 when one does not, 2 on
bad input. --plots DIR: the overlaid curves (needs matplotlib); --report FILE: both tables.
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PAPER = os.path.join(ROOT, "archive", "paper")
COMPARE = os.path.join(ROOT, "app", "spallbar_compare.py")

# Example 1: the paper's closed forms (doc/validation.md, "The paper's figures as archival
# data")
DT1, CELLS1, G = 5.0e-4, 20, 9.81
DM1, SIG1, DEL1 = 1.8e5 * DT1, 160.0e3, 60.0e3
N1 = range(3, 41)
# Example 3, case 1, the fixed bar
H, YOUNG, RHO = 0.95, 20.0e6, 1765.8
A = math.sqrt(YOUNG / RHO)


def load(t):
    return 0.1e6 * (1.0 - t / 0.5) ** 3 if 0.0 <= t < 0.5 else 0.0


def fixed_reaction(t):
    r, k = RHO * G * H, 0
    while t - (2 * k + 1) * H / A > 0.0:
        r += 2.0 * (-1) ** k * load(t - (2 * k + 1) * H / A)
        k += 1
    return r


def write_archive():
    os.makedirs(PAPER, exist_ok=True)
    with open(os.path.join(PAPER, "fig07c_example1.txt"), "w") as f:
        f.write("# Fig. 7c, Example 1: the splinter's translation V^n and vibration V~^n [m/s],\n"
                "# closed forms of the paper (doc/validation.md): V^n = [2 s_1 - d_1 + (n - 2.5)"
                " dm g] dt/dm,\n# V~^n = (-1)^n (d_1 + 0.5 dm g) dt/dm; s_1 = 160 kPa, d_1 = 60 "
                "kPa, dm = 90 kg/m^2, dt = 5e-4 s, g = 9.81\n"
                "# written by scripts/paper_curves.py --write-archive\n")
        f.write("n V V_vib\n")
        for n in N1:
            v = (2 * SIG1 - DEL1 + (n - 2.5) * DM1 * G) * DT1 / DM1
            vib = (-1.0) ** n * (DEL1 + 0.5 * DM1 * G) * DT1 / DM1
            f.write(f"{n} {v!r} {vib!r}\n")
    with open(os.path.join(PAPER, "fig10_fixed_reaction.txt"), "w") as f:
        f.write("# Fig. 10, the bar fixed in the base (dashed): base reaction R [Pa] (compression"
                " > 0) against t [s]\n# R = rho g h + 2 sum_k (-1)^k p(t - (2k+1) h/a), "
                "p = 0.1 (1 - t/0.5 s)^3 MPa, h = 0.95 m, E = 20 MPa, rho = 1765.8 kg/m^3\n"
                "# written by scripts/paper_curves.py --write-archive\n")
        f.write("t R\n")
        for k in range(4001):
            t = k * 2.5e-4
            f.write(f"{t!r} {fixed_reaction(t)!r}\n")
    print(f"wrote {os.path.relpath(PAPER)}/fig07c_example1.txt, fig10_fixed_reaction.txt")


def run(exe, work, deck, overrides=None):
    """Run input/DECK from work (its load tables beside it) with &run variables replaced."""
    text = open(os.path.join(ROOT, "input", deck)).read()
    if overrides:
        keep = [l for l in text.splitlines()
                if not re.match(r"\s*(" + "|".join(overrides) + r")\s*=", l, re.IGNORECASE)]
        text = "\n".join(keep).replace("&run", "&run\n" + "".join(
            f"  {k} = {v}\n" for k, v in overrides.items()), 1) + "\n"
    for f in os.listdir(os.path.join(ROOT, "input")):
        if f.endswith(".txt"):
            shutil.copy(os.path.join(ROOT, "input", f), work)
    with open(os.path.join(work, deck), "w") as f:
        f.write(text)
    r = subprocess.run([exe, deck, "--quiet"], cwd=work, capture_output=True, text=True,
                       stdin=subprocess.DEVNULL)
    if r.returncode != 0:
        sys.exit(f"paper_curves: {deck}: exit {r.returncode}: {r.stderr.strip()}")
    return os.path.join(work, deck[:-4])


def example1_table(exe, work):
    """The program's V^n and V~^n of Example 1 as a table n V V_vib."""
    import h5py   # the project venv
    prefix = run(exe, work, "example1.nml", {"t_end": repr((CELLS1 - 1 + 41) * DT1),
                                             "hdf5": ".true.", "field_every": "1"})
    with h5py.File(prefix + ".h5", "r") as h:
        t = h["/fields/xt/t"][()]
        v = h["/fields/xt/v"][()]
    out = os.path.join(work, "example1_model.txt")
    with open(out, "w") as f:
        f.write("n V V_vib\n")
        for k, tk in enumerate(t):
            n = round(tk / DT1) - (CELLS1 - 1)        # the paper's n: t^0 = step 19
            if n < N1[0] or n > N1[-1]:
                continue
            row = v[k] if v.shape[0] == len(t) else v[:, k]
            v_end, v_top = row[2 * CELLS1 - 1], row[2 * CELLS1 - 2]   # the splinter's halves
            mean = 0.5 * (v_end + v_top)
            f.write(f"{n} {float(mean)!r} {float(v_end - mean)!r}\n")
    return out


def compare(tool, ref, cand, args, plots, name):
    cmd = [sys.executable, tool, ref, cand] + args
    if plots:
        cmd += ["--plot", os.path.join(plots, name + ".png")]
    r = subprocess.run(cmd, capture_output=True, text=True, stdin=subprocess.DEVNULL)
    if r.returncode == 2:
        sys.exit(f"paper_curves: {r.stderr.strip()}")
    return r


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--exe")
    p.add_argument("--compare", default=COMPARE)
    p.add_argument("--work")
    p.add_argument("--plots")
    p.add_argument("--report")
    p.add_argument("--write-archive", action="store_true")
    a = p.parse_args()
    if a.write_archive:
        write_archive()
        return 0
    if not (a.exe and a.work):
        p.error("--exe and --work are needed to check")
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    if a.plots:
        os.makedirs(a.plots, exist_ok=True)
    exe = os.path.abspath(a.exe)
    ex1 = example1_table(exe, a.work)
    r1 = compare(a.compare, os.path.join(PAPER, "fig07c_example1.txt"), ex1,
                 ["--rtol", "1e-9"], a.plots, "paper_fig07c")
    fixed = run(exe, a.work, "example3_case1_fixed.nml") + ".his"
    dt = H / A / 19
    r2 = compare(a.compare, os.path.join(PAPER, "fig10_fixed_reaction.txt"), fixed,
                 ["--column", "R:reaction_bottom", "--rtol", "2e-3", "--time-tol",
                  repr(1.25 * dt)],
                 a.plots, "paper_fig10")
    text = ("## Fig. 7c, Example 1: V^n and V~^n against the paper's closed forms\n\n" + r1.stdout
            + "\n## Fig. 10, the bar fixed in the base: the reaction against the closed form\n\n"
            + r2.stdout)
    print(text)
    if a.report:
        with open(a.report, "w") as f:
            f.write(text)
    return 0 if r1.returncode == 0 and r2.returncode == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
