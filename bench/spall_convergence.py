#!/usr/bin/env python3
"""Mesh convergence of a concrete spall test, brittle against cohesive fracture (issue 31).

The deck (input/spall_cohesive.nml): a 1 m concrete bar (E = 35 GPa, rho = 2350 kg/m^3,
R = 8 MPa), free-free, a table pulse on the top face rising to 40 MPa at 25 us and falling
to 0 at 150 us, t_end = 1 ms. For each fracture energy (0: the paper's brittle fracture)
and mesh, the deck runs at strengths R (1 + 1e-6 u_k), u_k evenly spaced in [-1, 1]
(--realizations K; K = 1: R itself): the secondary fractures of a uniform-strength spall
zone are a bifurcation that a change of 1e-7 in R already decides otherwise
(doc/validation.md), so a mesh is judged by the ensemble. Per mesh: the fractures (cracks
opened fully) mean, standard deviation, min-max; the cracks that started; the first spall
plane (the first fracture in time) and its time; the scab,
from the topmost fracture to the free end, and the mean fragment size in it; e_cohesive;
the cohesive length E Gc / R^2 in cells; CPU time per run.

usage: spall_convergence.py --exe SPALLBAR [--cells 250,500,...] [--gc 0,100,300]
                            [--realizations K] [--jobs J] [--work DIR] [--table MD]
                            [--brittle-max-cells N]
Prints a Markdown table (and writes it with --table); exit 1 when a run failed.
"""
import argparse
import concurrent.futures
import math
import os
import subprocess
import sys
import time

E, RHO, R = 35e9, 2350.0, 8e6

DECK = """&run title = 'concrete spall, Gc = {gc:g} J/m^2', t_end = 1.0e-3, history_every = 100000,
     warnings = .false. /
&mesh cells = {cells} /
&segments n = 1, length = 1.0, young = 35e9, density = 2350, strength = {r!r},
  fracture_energy = {gc!r} /
&ends top = 'free', bottom = 'free' /
&load kind = 'table', face = 'top', table = 'spall_pulse.txt' /
"""
PULSE = "# t [s]  p [Pa]\n0.0      0.0\n25e-6    40e6\n150e-6   0.0\n"


def run_timed(cmd, cwd):
    """Run cmd; its exit status, its own CPU time (user + system, from wait4: not the other
    jobs') and its stderr."""
    with open(os.devnull, "w") as null:
        p = subprocess.Popen(cmd, cwd=cwd, stdout=null, stderr=subprocess.PIPE, text=True)
        err = p.stderr.read()
        _, status, ru = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
    return p.returncode, ru.ru_utime + ru.ru_stime, err.strip()


def one_run(exe, work, gc, cells, k, kk):
    u = 0.0 if kk == 1 else -1.0 + 2.0 * k / (kk - 1)
    name = f"spall_g{gc:g}_n{cells}_{k}"
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(DECK.format(gc=gc, cells=cells, r=R * (1.0 + 1e-6 * u)))
    for ext in (".his", ".evt", ".frg", ".prf", ".lock"):
        if os.path.exists(os.path.join(work, name + ext)):
            os.remove(os.path.join(work, name + ext))
    rc, cpu, err = run_timed([exe, name + ".nml", "-o", name, "-q"], work)
    if rc != 0:
        return {"ok": False, "why": err[:200], "name": name}
    fr, cracks = [], 0
    for line in open(os.path.join(work, name + ".evt")):
        if not line.startswith(" "):
            continue
        w = line.split()
        if w[2] == "fracture":
            fr.append((float(w[0]), float(w[4])))
        elif w[2] == "crack":
            cracks += 1
    hdr, last = None, None
    for line in open(os.path.join(work, name + ".his")):
        if line.startswith("#"):
            continue
        if hdr is None:
            hdr = line.split()
        elif line.strip():
            last = line.split()
    h = dict(zip(hdr, map(float, last)))
    os.remove(os.path.join(work, name + ".evt"))
    first = min(fr) if fr else (math.nan, math.nan)
    top = min(x for _, x in fr) if fr else math.nan
    return {"ok": True, "fractures": len(fr), "cracks": cracks, "t_first": first[0],
            "x_first": first[1], "scab": 1.0 - top, "piece": (1.0 - top) / max(1, len(fr)),
            "e_cohesive": h.get("e_cohesive", 0.0), "cpu": cpu, "name": name}


def stats(xs):
    m = sum(xs) / len(xs)
    s = math.sqrt(sum((x - m)**2 for x in xs) / max(1, len(xs) - 1))
    return m, s


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--cells", default="250,500,1000,2000,4000,8000")
    ap.add_argument("--gc", default="0,100,300")
    ap.add_argument("--realizations", type=int, default=8)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--work", default="build/release/spall_convergence")
    ap.add_argument("--table")
    ap.add_argument("--brittle-max-cells", type=int, default=4000,
                    help="brittle runs only up to this mesh (their events grow as N^2)")
    a = ap.parse_args(argv[1:])
    os.makedirs(a.work, exist_ok=True)
    with open(os.path.join(a.work, "spall_pulse.txt"), "w") as f:
        f.write(PULSE)
    exe = os.path.abspath(a.exe)
    cells = [int(x) for x in a.cells.split(",")]
    gcs = [float(x) for x in a.gc.split(",")]
    jobs = []
    for gc in gcs:
        for n in cells:
            if gc == 0.0 and n > a.brittle_max_cells:
                continue
            kk = 1 if gc == 0.0 else a.realizations
            jobs += [(gc, n, k, kk) for k in range(kk)]
    res, failed = {}, 0
    t_all = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        futs = {ex.submit(one_run, exe, a.work, *j): j for j in jobs}
        for fu in concurrent.futures.as_completed(futs):
            gc, n, k, kk = futs[fu]
            r = fu.result()
            if not r["ok"]:
                failed += 1
                print(f"spall_convergence.py: {r['name']}: {r['why']}", file=sys.stderr)
                continue
            res.setdefault((gc, n), []).append(r)
    lines = ["| Gc [J/m²] | cells | dx [mm] | E Gc/R² [cells] | runs | fractures mean ± sd "
             "(min–max) | cracks started | first spall plane x [m] (t [µs]) | scab [m] | mean "
             "piece in it [mm] | e_cohesive [J/m²] | CPU per run [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for gc in gcs:
        for n in cells:
            rs = res.get((gc, n))
            if not rs:
                continue
            f_m, f_s = stats([r["fractures"] for r in rs])
            lz = E * gc / R**2 / (1.0 / n)
            lines.append(
                f"| {gc:g} | {n} | {1000.0 / n:.3g} | {lz:.1f} | {len(rs)} | "
                f"{f_m:.2f} ± {f_s:.2f} ({min(r['fractures'] for r in rs)}–"
                f"{max(r['fractures'] for r in rs)}) | {stats([r['cracks'] for r in rs])[0]:.0f} | "
                f"{stats([r['x_first'] for r in rs])[0]:.4f} ({1e6 * stats([r['t_first'] for r in rs])[0]:.1f}) | "
                f"{stats([r['scab'] for r in rs])[0]:.3f} | {1000 * stats([r['piece'] for r in rs])[0]:.1f} | "
                f"{stats([r['e_cohesive'] for r in rs])[0]:.1f} | {stats([r['cpu'] for r in rs])[0]:.2f} |")
    text = "\n".join(lines)
    print(text)
    print(f"{len(jobs) - failed} runs, wall {time.time() - t_all:.0f} s on {a.jobs} jobs")
    if a.table:
        with open(a.table, "w") as f:
            f.write("<!-- made by bench/spall_convergence.py; do not edit -->\n" + text + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
