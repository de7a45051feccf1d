#!/usr/bin/env python3
"""spallbar benchmarks (`make bench`): whole-process wall times, medians of several runs.

  intact    intact bar, N = 100 000 cells, 2000 steps: node-steps/s, and in the same run
            two references of the same compact scheme (bench/references.py): a lean NumPy
            loop (bench/numpy_ref.py) and a naive Fortran loop (bench/naive_ref.f90,
            compiled here with spallbar's Release flags); first a check that both compute
            spallbar's final state (u, v, stress) to TOLERANCE; then the superseded NumPy
            reference (numpy_ref.py --variant old), timed once, for the record
  case2     the paper's Example 3 case 2 at h/190 (input/example3_case2/), outputs as in
            the decks (history every step, every event)
  output    case 2 at h/19 with history every step vs none: the share output costs
  rings     issue 36's target 1: a breakable homogeneous bar of 1e6 cells (concrete, the
            triangular pulse of input/spall_test.nml) to its first fracture (1 077 187
            steps, history rows at steps 0, 1e6 and the end only), in characteristic form
            (spb_ring): effective node-steps/s = N steps / CPU s of the whole process, and
            / the naive loop's node-steps/s (bench/naive_ref.f90, N = 1e6, 200 steps, CPU s)
  scaling   time per node-step for N = 1e3 .. 1e6 (intact); for N = 1e5 flying apart in
            1, 10, 100 fragments; wall time vs event count over the six case-2 decks at
            h/95 and h/190 (slope = cost per event; h/19 has too few events to
            time)

usage: run.py --exe SPALLBAR [--repeats 5] [--table doc/benchmarks.md] [--plot PNG]
              [--fc gfortran]
"""
import argparse
import math
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

from references import (TOLERANCE, build_naive, check, describe, intact_deck,
                        release_flags, worst)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

def timed(cmd, cwd, repeats):
    walls = []
    for _ in range(repeats):
        t = time.perf_counter()
        subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL)
        walls.append(time.perf_counter() - t)
    return statistics.median(walls), min(walls), max(walls)


FLYING = """&run
  title = 'flying fragments benchmark'
  t_end = {t_end}
  history_every = 1000000000
/
&mesh
  dt = 1.0e-6
/
&segments
  n = {k}
  length = {k}*{length}
  young = {k}*2.0e11
  density = {k}*8000.0
{dry}  velocity = {velocity}
/
&ends
  top = 'free'
  bottom = 'free'
/
"""


def flying_deck(work, cells, steps, k):
    """N cells in k segments, dry interfaces, each segment faster than the one above it:
    k - 1 open sections from the first step and no event after."""
    path = os.path.join(work, f"flying_{cells}_{k}.nml")
    with open(path, "w") as f:
        f.write(FLYING.format(t_end=f"{steps * 1.0e-6:.10g}", k=k,
                              length=f"{cells // k * 5.0e-3:.10g}",
                              dry=("  interface = " + ", ".join(["'dry'"] * (k - 1)) + "\n") if k > 1 else "",
                              velocity=", ".join(f"{j:.1f}" for j in range(k))))
    return path


def linear_fit(x, y):
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((a - mx) ** 2 for a in x)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    slope = sxy / sxx
    return slope, my - slope * mx


def count_events(prefix):
    with open(prefix + ".evt") as f:
        return sum(1 for line in f if line.startswith(" "))


def no_history(work, deck, name):
    text = open(deck).read().replace("&run", "&run\n  history_every = 1000000000", 1)
    path = os.path.join(work, name + ".nml")
    with open(path, "w") as f:
        f.write(text)
    return path


def timed_together(cmds, cwd, repeats):
    """Run the commands of CMDS ({name: argv}) one after the other, REPEATS rounds, so that
    the VM's slow and fast spells fall on all of them alike. Returns {name: (median, min,
    max wall, median of the 'loop T s' the program printed, or None)}."""
    walls = {k: [] for k in cmds}
    loops = {k: [] for k in cmds}
    for _ in range(repeats):
        for name, cmd in cmds.items():
            t = time.perf_counter()
            out = subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.PIPE,
                                 text=True).stdout
            walls[name].append(time.perf_counter() - t)
            m = re.search(r"loop\s+([0-9.]+) s", out)
            if m:
                loops[name].append(float(m.group(1)))
    return {k: (statistics.median(w), min(w), max(w),
                statistics.median(loops[k]) if loops[k] else None) for k, w in walls.items()}


def intact_rows(exe, work, rep, fc):
    """The intact bar against its two references (bench/references.py), timed in the same
    rounds, after a check that they compute what spallbar computes."""
    cells, steps = 100000, 2000
    naive, naive_cmd = build_naive(work, fc, release_flags(exe))
    result = check(exe, work, cells, steps, naive)
    if not worst(result) <= TOLERANCE:
        raise SystemExit(f"references disagree with spallbar beyond {TOLERANCE:.0e}: "
                         f"{describe(result)}")
    numpy_ref = os.path.join(HERE, "numpy_ref.py")
    cmds = {"spallbar": [exe, intact_deck(work, cells, steps), "-q"],
            # start-up, deck, set-up of 1e5 nodes and outputs: the same deck for one step
            "spallbar_1": [exe, intact_deck(work, cells, 1), "-q"],
            "naive": [naive, str(cells), str(steps)],
            "numpy": [sys.executable, numpy_ref, str(cells), str(steps)]}
    r = timed_together(cmds, work, rep)
    old = timed_together({"old": [sys.executable, numpy_ref, str(cells), str(steps),
                                  "--variant", "old"]}, work, max(3, rep // 2))["old"]
    ns = (cells + 1) * steps
    spb, spb1 = r["spallbar"], r["spallbar_1"]
    spb_steps = spb[0] - spb1[0]

    def span(x):
        return f"{x[0]:.3f} s ({x[1]:.3f}-{x[2]:.3f})"

    rows = [("intact bar, N = 1e5, 2000 steps", span(spb),
             f"{ns / spb[0]:.3g} node-steps/s; the same deck for 1 step (start-up, set-up, "
             f"outputs) {spb1[0]:.3f} s, so the steps take {spb_steps:.3f} s")]
    for key, what in (("naive", "naive Fortran loop (bench/naive_ref.f90, Release flags)"),
                      ("numpy", "NumPy, lean loop (bench/numpy_ref.py)")):
        x = r[key]
        rows.append((f"{what}, same scheme and size", span(x),
                     f"its time loop {x[3]:.3f} s ({ns / x[3]:.3g} node-steps/s); "
                     f"spallbar / {key} = **{x[0] / spb[0]:.2f}** whole process, "
                     f"**{x[3] / spb_steps:.2f}** time steps only"))
    rows.append(("superseded NumPy reference (NumPy-scalar stiffness, temporaries; "
                 "`numpy_ref.py --variant old`)", span(old),
                 f"its time loop {old[3]:.3f} s; spallbar / old = {old[0] / spb[0]:.2f} whole "
                 f"process (the ratio the tables before issue 21 reported)"))
    rows.append(("check: both references against spallbar's profile at t_end, N = 1e5, "
                 "2000 steps", "-",
                 f"max |ref - spallbar| / max |spallbar|: {describe(result)} "
                 f"(tolerance {TOLERANCE:.0e}); naive built with `{naive_cmd}`"))
    return rows


def ring_deck(work, cells, t_end):
    """input/spall_test.nml (the concrete spall bar) with cells, t_end, history rows every 1e6
    steps and no gauge (a gauge row every step would end every span)."""
    with open(os.path.join(ROOT, "input", "spall_test.nml")) as f:
        text = f.read()
    text = text[:text.index("&gauges")]
    text = re.sub(r"cells *= *\d+", f"cells = {cells}", text)
    text = re.sub(r"t_end *= *[0-9.eE+-]+", f"t_end = {t_end!r}", text)
    text = re.sub(r"history_every *= *\d+", "history_every = 1000000", text)
    path = os.path.join(work, "rings1m.nml")
    with open(path, "w") as f:
        f.write(text)
    return path


def cpu_run(cmd, cwd):
    """CPU seconds (user + system) of one run of cmd, and its stdout."""
    t0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.PIPE, text=True).stdout
    t1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (t1.ru_utime - t0.ru_utime) + (t1.ru_stime - t0.ru_stime), out


def ring_rows(exe, work, rep, fc):
    """Issue 36's target 1 (>= 1e11 effective node-steps/s, >= 100x the naive loop): the
    spall bar of 1e6 cells to its first fracture at step 1 077 186 (the first of its
    reflected tension, 0.922 m down), then one more step."""
    cells, steps = 1000000, 1077187
    t_end = (steps - 0.5) / (math.sqrt(35.0e9 / 2350.0) * cells)
    deck = ring_deck(work, cells, t_end)
    naive, _ = build_naive(work, fc, release_flags(exe))
    cpu, loops = [], []
    for _ in range(max(1, rep // 2)):
        c, _ = cpu_run([exe, deck, "-q", "--output", os.path.join(work, "rings1m")], work)
        cpu.append(c)
        # its CPU time too (the process, set-up included: a loaded machine stretches the
        # wall time its loop prints)
        c, _ = cpu_run([naive, str(cells), "200"], work)
        loops.append(c)
    with open(os.path.join(work, "rings1m.evt")) as f:
        first = [line.split() for line in f if line.startswith(" ")][:1]
    c, lp = statistics.median(cpu), statistics.median(loops)
    rate = cells * steps / c
    naive_rate = (cells + 1) * 200 / lp
    what = (f"step {first[0][1]}, node {first[0][3]}, {float(first[0][5]) / 1e6:.4f} MPa"
            if first else "none")
    return [("issue 36 target 1: breakable homogeneous bar, N = 1e6, to its first fracture "
             f"({steps} steps, 3 history rows; characteristic steps, spb_ring)",
             f"{c:.2f} s CPU ({min(cpu):.2f}-{max(cpu):.2f})",
             f"**{rate:.3g}** effective node-steps/s (target 1e11); naive loop "
             f"{naive_rate:.3g} node-steps/s (N = 1e6, 200 steps, CPU s of its process): "
             f"**{rate / naive_rate:.0f}x** "
             f"(target 100x); first fracture {what}")]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", required=True)
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--table", help="write the Markdown table here")
    p.add_argument("--plot", help="write the scaling plot here")
    p.add_argument("--label", default="this build")
    p.add_argument("--fc", default="gfortran", help="compiler for bench/naive_ref.f90")
    args = p.parse_args()
    exe = os.path.abspath(args.exe)
    rep = args.repeats
    rows, notes = [], []
    with tempfile.TemporaryDirectory() as work:
        rows += intact_rows(exe, work, rep, args.fc)
        rows += ring_rows(exe, work, rep, args.fc)
        # case 2 at h/190
        for rule in ("accelerate_fragment", "accelerate_above", "delay_fragment",
                     "min_fragment"):
            deck = os.path.join(ROOT, "input", "example3_case2", f"{rule}_h190.nml")
            prefix = os.path.join(work, rule)
            med, lo, hi = timed([exe, deck, "-q", "--output", prefix], work, rep)
            ev = count_events(prefix)
            nmed, _, _ = timed([exe, no_history(work, deck, rule + "_nh"), "-q", "--output",
                                prefix + "_nh"], work, rep)
            rows.append((f"Example 3 case 2, {rule.replace('_', '/')}, h/190 (12 772 steps)",
                         f"{med:.3f} s ({lo:.3f}-{hi:.3f})",
                         f"{ev} events; without the history rows {nmed:.3f} s"))
        # output share at N = 19
        deck = os.path.join(ROOT, "input", "example3_case2", "accelerate_fragment_h19.nml")
        w_med, _, _ = timed([exe, deck, "-q", "--output", os.path.join(work, "o19")], work,
                            rep * 2)
        n_med, _, _ = timed([exe, no_history(work, deck, "o19nh"), "-q", "--output",
                             os.path.join(work, "o19nh")], work, rep * 2)
        rows.append(("output share: case 2 at h/19 (N = 19, 1278 steps), history every step",
                     f"{w_med:.4f} s vs {n_med:.4f} s without",
                     f"history rows cost {100 * (w_med - n_med) / w_med:.0f}% of the run "
                     "(process start and deck echo included in both)"))
        # scaling with N (intact), with the number of fragments, and with the event count
        sizes, per_node = [1000, 10000, 100000, 1000000], []
        for n in sizes:
            st = max(20, int(2.0e7 / n))
            med, _, _ = timed([exe, intact_deck(work, n, st), "-q"], work, 3)
            per_node.append(med / ((n + 1) * st) * 1e9)
        rows.append(("time per node-step, intact bar, N = 1e3, 1e4, 1e5, 1e6",
                     ", ".join(f"{x:.2f} ns" for x in per_node), "flat = O(N) per step"))
        pieces, per_frag = [1, 10, 100], []
        for k in pieces:
            med, _, _ = timed([exe, flying_deck(work, 100000, 200, k), "-q"], work, 3)
            per_frag.append(med / (100001 * 200) * 1e9)
        rows.append(("time per node-step, N = 1e5 flying apart in 1, 10, 100 fragments "
                     "(no events after t = 0)", ", ".join(f"{x:.2f} ns" for x in per_frag),
                     "flat = independent of the number of fragments"))
        fits = {}
        for cells in (95, 190):
            evs, walls = [], []
            for rule in ("accelerate", "delay", "min"):
                for pol in ("above", "fragment"):
                    deck = os.path.join(ROOT, "input", "example3_case2",
                                        f"{rule}_{pol}_h{cells}.nml")
                    prefix = os.path.join(work, f"ev{cells}_{rule}_{pol}")
                    med, _, _ = timed([exe, no_history(work, deck, f"ev{cells}{rule}{pol}"),
                                       "-q", "--output", prefix], work, 3)
                    evs.append(count_events(prefix))
                    walls.append(med)
            slope, icpt = linear_fit(evs, walls)
            fits[cells] = (evs, walls, slope, icpt)
        rows.append(("wall time vs events, case 2 without history rows, the 6 rule/policy "
                     "decks at h/95 and h/190 (least-squares slope)",
                     ", ".join(f"{fits[c][2] * 1e6:.2f} us/event" for c in (95, 190)),
                     "events " + "; ".join(f"h/{c}: {min(fits[c][0])}-{max(fits[c][0])}"
                                           for c in (95, 190))))
    lines = [f"| case ({args.label}) | median wall (min-max) | result |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    text = "\n".join(lines)
    print(text)
    if args.table:
        with open(args.table, "w") as f:
            f.write(text + "\n")
    if args.plot:
        os.environ.setdefault("MPLBACKEND", "Agg")
        import matplotlib.pyplot as plt
        fig, (a1, a2, a3) = plt.subplots(1, 3, figsize=(13, 3.8))
        a1.loglog(sizes, per_node, "o-", color="C0")
        a1.set_ylim(min(per_node) / 3, max(per_node) * 3)
        a1.set_xlabel("cells N")
        a1.set_ylabel("wall time per node-step [ns]")
        a1.set_title("intact bar: cost per node-step vs N", fontsize=9)
        a2.semilogx(pieces, per_frag, "o-", color="C0")
        a2.set_ylim(0, max(per_frag) * 1.5)
        a2.set_xlabel("fragments (N = 1e5, 200 steps)")
        a2.set_ylabel("wall time per node-step [ns]")
        a2.set_title("no events: cost per step vs number of fragments", fontsize=9)
        # one colour per series: its points, its least-squares line and its legend entry
        # (a proxy drawn with both the marker and the line)
        for c, mk, col in zip((95, 190), ("o", "s"), ("C0", "C1")):
            evs, walls, slope, icpt = fits[c]
            a3.plot(evs, walls, mk, color=col, linestyle="none")
            xs = [0, max(evs)]
            a3.plot(xs, [icpt + slope * x for x in xs], "-", color=col, lw=0.8)
            a3.plot([], [], mk + "-", color=col, lw=0.8,
                    label=f"h/{c}: runs and fit, {slope * 1e6:.2f} us/event")
        a3.set_xlabel("events in the run (case 2, 6 rule/policy decks)")
        a3.set_ylabel("wall time [s]")
        a3.set_title("case 2: wall time vs event count", fontsize=9)
        a3.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
