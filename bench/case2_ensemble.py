#!/usr/bin/env python3
"""Ensembles of Example 3 case 2 (issue 34): predictability horizons and ensemble statistics.

    case2_ensemble.py --exe PATH/spallbar --work DIR [--cells 19,95,190] [--realizations 64]
                      [--spread 1e-3] [--policies above,fragment] [--times 0.1,0.3,0.6]
                      [--horizon-tol 0.01] [--ranks 1] [--mpirun mpirun] [--table OUT.md]

For each shift policy (timing 'accelerate', the default event rules) and each mesh (cells per
h), one `spallbar --sweep` of case 2 (input/example3_case2/accelerate_<policy>_h19.nml with
`&mesh cells` replaced, profile_times dropped, t_end 0.6 s) with

    &sweep perturb = 'p0', spread = SPREAD, realizations = R,
           ensemble_columns = 'reaction_bottom', 'e_lost_w', 'i_support' /

(doc/sweeps.md, "Ensembles"). From each PREFIX.ens: the predictability horizon of each
column (the first 1 ms window whose std over the realizations of the window means exceeds
horizon_tol x the largest |window mean|), and the ensemble mean +- std (population) of
e_lost_w, of the base impulse I = -i_support and of the base reaction at the history rows
nearest the --times. Prints Markdown tables (and --table writes them) and the wall and CPU
time of each sweep (`make case2-ensemble`: 64 realizations, about 45 s CPU on this VM).
Plain Python. Exit 0; 1 if a sweep failed.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
COLUMNS = ("reaction_bottom", "e_lost_w", "i_support")


def deck_text(policy, cells, realizations, spread, tol):
    """Case 2, accelerate/POLICY, h/CELLS, as an ensemble sweep."""
    path = os.path.join(ROOT, "input", "example3_case2", f"accelerate_{policy}_h19.nml")
    text = open(path).read()
    text = re.sub(r"\n\s*profile_times[^\n]*", "", text)
    text = text.replace("cells = 19", f"cells = {cells}")
    text = re.sub(r"title\s*=[^\n]*", f"title = 'case 2 ensemble, accelerate/{policy}, "
                  f"h/{cells}'", text)
    assert f"cells = {cells}" in text
    return text + (f"&sweep\n  perturb = 'p0'\n  spread = {spread!r}\n  realizations = "
                   f"{realizations}\n  seed = 2026\n  ensemble_columns = "
                   + ", ".join(f"'{c}'" for c in COLUMNS) + f"\n  horizon_tol = {tol!r}\n/\n")


def read_ens(path):
    """PREFIX.ens: {column: [values]}, {column: horizon [s] or None}, the header."""
    names, rows, horizon, head = None, [], {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                head.append(line.rstrip("\n"))
                m = re.match(r"# horizon (\w+): (\S+)", line)
                if m:
                    try:
                        horizon[m.group(1)] = float(m.group(2))
                    except ValueError:
                        horizon[m.group(1)] = None
                names = line[1:].split()
            elif line.startswith(" ") and line.strip():
                rows.append([float(x) for x in line.split()])
    return {n: [r[k] for r in rows] for k, n in enumerate(names)}, horizon, head


def nearest(t, target):
    return min(range(len(t)), key=lambda k: abs(t[k] - target))


def main():
    p = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    p.add_argument("--exe", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--cells", default="19,95,190")
    p.add_argument("--realizations", type=int, default=64)
    p.add_argument("--spread", type=float, default=1e-3)
    p.add_argument("--policies", default="above,fragment")
    p.add_argument("--times", default="0.1,0.3,0.6")
    p.add_argument("--horizon-tol", type=float, default=0.01)
    p.add_argument("--ranks", type=int, default=1, help="MPI ranks per sweep (1: no mpirun)")
    p.add_argument("--mpirun", default="mpirun")
    p.add_argument("--table", help="also write the tables (Markdown) here")
    a = p.parse_args()
    exe = os.path.abspath(a.exe)
    os.makedirs(a.work, exist_ok=True)
    cells = [int(c) for c in a.cells.split(",")]
    times = [float(t) for t in a.times.split(",")]
    policies = a.policies.split(",")
    results, failed, total, total_cpu = {}, 0, 0.0, 0.0
    for policy in policies:
        for n in cells:
            name = f"ens_{policy}_h{n}"
            with open(os.path.join(a.work, name + ".nml"), "w") as f:
                f.write(deck_text(policy, n, a.realizations, a.spread, a.horizon_tol))
            cmd = [exe, "--sweep", name + ".nml", "-q"]
            if a.ranks > 1:
                cmd = [a.mpirun, "--oversubscribe", "-np", str(a.ranks)] + cmd
            t0 = time.monotonic()
            c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            r = subprocess.run(cmd, cwd=a.work, capture_output=True, text=True,
                               stdin=subprocess.DEVNULL)
            c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            wall = time.monotonic() - t0
            cpu = (c1.ru_utime + c1.ru_stime) - (c0.ru_utime + c0.ru_stime)
            total += wall
            total_cpu += cpu
            if r.returncode != 0:
                print(f"{name}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
                failed += 1
                continue
            cols, horizon, head = read_ens(os.path.join(a.work, name + ".ens"))
            members = next((h for h in head if h.startswith("# ensemble: ")), "")
            results[(policy, n)] = (cols, horizon, (wall, cpu), members)
            print(f"{name}: {wall:.1f} s wall, {cpu:.1f} s CPU; {members[12:40]}", flush=True)
    out = []
    out.append(f"Example 3 case 2, timing 'accelerate', default event rules, p0 x (1 + "
               f"{a.spread:g} u), {a.realizations} realizations, horizon_tol "
               f"{a.horizon_tol:g} (1 ms windows); horizons in s ('-': not reached before "
               f"t_end):\n")
    out.append("| policy | mesh | horizon reaction_bottom | horizon e_lost_w | "
               "horizon I = -i_support | sweep wall, CPU [s] |")
    out.append("|---|---|---|---|---|---|")
    for (policy, n), (cols, horizon, wall, _) in results.items():
        hz = [horizon.get(c) for c in COLUMNS]
        out.append(f"| {policy} | h/{n} | " + " | ".join("-" if h is None else f"{h:g}"
                                                        for h in hz) +
                   f" | {wall[0]:.1f}, {wall[1]:.1f} |")
    for label, col, sign, unit in (("e_lost_w", "e_lost_w", 1.0, "J/m^2"),
                                   ("base impulse I = -i_support", "i_support", -1.0,
                                    "kg/(m s)"),
                                   ("base reaction (one history row)", "reaction_bottom", 1.0,
                                    "kPa")):
        scale = 1e3 if unit == "kPa" else 1.0
        out.append(f"\nEnsemble mean ± std of {label} [{unit}] at the history row nearest t:\n")
        out.append("| policy | mesh | " + " | ".join(f"t = {t:g} s" for t in times) + " |")
        out.append("|---|---|" + "---|" * len(times))
        for (policy, n), (cols, _, _, _) in results.items():
            cells_text = []
            for t in times:
                k = nearest(cols["t"], t)
                m = sign * cols[f"{col}_mean"][k] / scale
                s = cols[f"{col}_std"][k] / scale
                cells_text.append(f"{m:.4g} ± {s:.3g}")
            out.append(f"| {policy} | h/{n} | " + " | ".join(cells_text) + " |")
    out.append(f"\nAll sweeps: {total:.1f} s wall, {total_cpu:.1f} s CPU ({a.ranks} rank(s) "
               "each).")
    text = "\n".join(out)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
