#!/usr/bin/env python3
"""Consistency of the event corrections under refinement (issue 34): a measurement.

    consistency.py --exe PATH/spallbar --work DIR [--json OUT.json] [--jobs K]
                   [--only drop,pair,example2,case2] [--case2-meshes 19,95,190]

For a fixed physical sequence of events the corrections an event makes (the rigid shifts of
(5.2), the join's loss) should vanish as the step does. This script measures how fast, for
every timing x shift rule (and the paper's rules), on three isolated-event decks:

  drop      an elastic bar (0.5 m, c = 1000 m/s) falls at 1 m/s onto the base from a gap,
            lands, lifts off after 2L/c and flies off (g = 0): one landing, one lift-off;
  pair      two bars (0.3 and 0.2 m) meet head-on at 2 m/s through a dry gap and separate:
            one collision, one separation;
  example2  the seed's Example 2 (input/example2.nml): spall in a layered semi-infinite bar,
            the top piece pushed back into the next one (fractures and collisions);

each on four meshes (dt, dt/2, dt/4, dt/8), the drop and the pair at four offsets of the event
within its step (the gap set to v (k + theta) dt, theta = 0.13, 0.37, 0.61, 0.89: a mean over
where the event falls). Read at t_end from PREFIX.his: |x_drift| (the centre of mass's
displacement no momentum paid for) and e_lost_w (the wave energy the events removed), as means
over the offsets; the order between two meshes is log2(err(h) / err(h/2)).

Then Example 3 case 2 (input/example3_case2, zero tensile strength on the base) for every
rule on the meshes of --case2-meshes (h/19, h/95, h/190 by default): e_lost_w at 0.6 s, the
base's impulse (-i_support) and x_drift.

Prints the tables (Markdown) and writes every number to --json. Exit 0; 1 if a run failed.
"""
import argparse
import concurrent.futures
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

RULES = [("accelerate", "above", "admissible"), ("accelerate", "fragment", "admissible"),
         ("delay", "above", "admissible"), ("delay", "fragment", "admissible"),
         ("min", "above", "admissible"), ("min", "fragment", "admissible"),
         ("accelerate", "face", "admissible"), ("delay", "face", "admissible"),
         ("min", "face", "admissible"), ("within", "above", "admissible"),
         ("accelerate", "above", "paper")]
THETAS = (0.13, 0.37, 0.61, 0.89)
LEVELS = (1, 2, 4, 8)


def run_rules(timing, shift, events):
    return f"timing = '{timing}', shift = '{shift}', events = '{events}', warnings = .false."


def drop_deck(rule, level, theta):
    """The bar falling onto the base."""
    dt = 1e-5 / level
    v0, length, c = 1.0, 0.5, 1000.0
    gap = v0 * (3 + theta) * dt
    t_end = gap / v0 + 3.0 * length / c
    return (f"&run t_end = {t_end!r}, history_every = 1000000, {run_rules(*rule)} /\n"
            f"&mesh dt = {dt!r} /\n"
            f"&segments n = 1, length = {length!r}, young = 2e9, density = 2000, "
            f"velocity = {v0!r} /\n"
            f"&ends top = 'free', bottom = 'base', base_gap = {gap!r} /\n")


def pair_deck(rule, level, theta):
    """Two bars meeting head-on through a dry gap."""
    dt = 1e-5 / level
    v0, c = 1.0, 1000.0
    gap = 2.0 * v0 * (3 + theta) * dt
    t_end = gap / (2.0 * v0) + 3.0 * 0.3 / c
    return (f"&run t_end = {t_end!r}, history_every = 1000000, {run_rules(*rule)} /\n"
            f"&mesh dt = {dt!r} /\n"
            f"&segments n = 2, length = 0.3, 0.2, young = 2e9, 2e9, density = 2000, 2000, "
            f"velocity = {v0!r}, {-v0!r}, interface = 'dry', gap = {gap!r} /\n"
            f"&ends top = 'free', bottom = 'free' /\n")


def example2_deck(rule, level, theta=None):
    """The seed's Example 2 with the step divided by level."""
    with open(os.path.join(ROOT, "input", "example2.nml")) as f:
        text = f.read()
    text = text.replace("dt = 8.0e-6", f"dt = {8.0e-6 / level!r}")
    text = text.replace("history_every = 1", "history_every = 1000000")
    text = text.replace("&run\n", f"&run\n  {run_rules(*rule)}\n", 1)
    return "\n".join(l for l in text.splitlines() if not l.strip().startswith("profile_times"))


def case2_deck(rule, cells):
    """Example 3 case 2 on the base at h/cells, 0.6 s."""
    with open(os.path.join(ROOT, "input", "example3_case2", "accelerate_above_h19.nml")) as f:
        text = f.read()
    timing, shift, events = rule
    text = text.replace("timing        = 'accelerate'", f"timing = '{timing}'")
    text = text.replace("shift         = 'above'", f"shift = '{shift}', events = '{events}', "
                        "warnings = .false., history_every = 1000000")
    text = text.replace("cells = 19", f"cells = {cells}")
    return "\n".join(l for l in text.splitlines() if not l.strip().startswith("profile_times"))


def last_row(path):
    """The last row of PREFIX.his by column name."""
    names, row = None, None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                names = line[1:].split()
            elif line.startswith(" ") and line.strip():
                row = line
    return {k: float(v) for k, v in zip(names, row.split())}


def run_one(exe, work, name, deck):
    path = os.path.join(work, name + ".nml")
    with open(path, "w") as f:
        f.write(deck)
    r = subprocess.run([exe, path, "--output", os.path.join(work, name), "--quiet"],
                       capture_output=True, text=True, stdin=subprocess.DEVNULL)
    if r.returncode != 0:
        return name, None, r.stderr.strip()
    return name, last_row(os.path.join(work, name + ".his")), ""


def order(a, b):
    if a > 0 and b > 0:
        return f"{math.log2(a / b):.2f}"
    return "-"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--json")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="drop,pair,example2,case2")
    ap.add_argument("--case2-meshes", default="19,95,190")
    args = ap.parse_args(argv)
    os.makedirs(args.work, exist_ok=True)
    exe = os.path.abspath(args.exe)
    only = set(args.only.split(","))
    jobs = []
    builders = {"drop": drop_deck, "pair": pair_deck, "example2": example2_deck}
    for deck_name, build in builders.items():
        if deck_name not in only:
            continue
        thetas = THETAS if deck_name != "example2" else (None,)
        for ri, rule in enumerate(RULES):
            for level in LEVELS:
                for ti, theta in enumerate(thetas):
                    jobs.append((f"{deck_name}_r{ri}_l{level}_t{ti}", build(rule, level, theta)))
    meshes = [int(m) for m in args.case2_meshes.split(",")] if "case2" in only else []
    for ri, rule in enumerate(RULES):
        for cells in meshes:
            jobs.append((f"case2_r{ri}_h{cells}", case2_deck(rule, cells)))
    results, failed = {}, 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name, row, err in pool.map(lambda j: run_one(exe, args.work, *j), jobs):
            results[name] = row
            if row is None:
                failed += 1
                print(f"FAILED {name}: {err}", file=sys.stderr)
    tables = {}
    for deck_name in [d for d in builders if d in only]:
        print(f"\n### {deck_name}: mean |x_drift| [m] and e_lost_w [J/m^2] at t_end, dt / "
              f"{', '.join(str(l) for l in LEVELS)}, and the orders between meshes\n")
        print("| rule | " + " | ".join(f"x_drift dt/{l}" for l in LEVELS) + " | order | "
              + " | ".join(f"e_lost_w dt/{l}" for l in LEVELS) + " | order | "
              + " | ".join(f"l_defect dt/{l}" for l in LEVELS) + " | order |")
        print("|---" * (3 * len(LEVELS) + 4) + "|")
        for ri, rule in enumerate(RULES):
            xs, es, ls = [], [], []
            for level in LEVELS:
                rows = [v for k, v in results.items()
                        if k.startswith(f"{deck_name}_r{ri}_l{level}_") and v]
                xs.append(sum(abs(r.get("x_drift", float("nan"))) for r in rows) / max(len(rows), 1))
                es.append(sum(abs(r["e_lost_w"]) for r in rows) / max(len(rows), 1))
                ls.append(sum(abs(r.get("l_defect", float("nan"))) for r in rows)
                          / max(len(rows), 1))
            tables.setdefault(deck_name, {})["/".join(rule)] = {"x_drift": xs, "e_lost_w": es,
                                                                "l_defect": ls}
            print(f"| {'/'.join(rule)} | " + " | ".join(f"{x:.2e}" for x in xs)
                  + f" | {order(xs[-2], xs[-1])} | " + " | ".join(f"{e:.2e}" for e in es)
                  + f" | {order(es[-2], es[-1])} | " + " | ".join(f"{x:.2e}" for x in ls)
                  + f" | {order(ls[-2], ls[-1])} |")
    if meshes:
        print("\n### Example 3 case 2 at 0.6 s: e_lost_w [J/m^2], base impulse -i_support "
              "[kg/(m s)], x_drift [m], l_defect [m]\n")
        print("| rule | " + " | ".join(f"e_lost_w h/{m} | impulse h/{m} | x_drift h/{m} | "
                                       f"l_defect h/{m}" for m in meshes) + " |")
        print("|---" * (4 * len(meshes) + 1) + "|")
        for ri, rule in enumerate(RULES):
            cells = []
            for m in meshes:
                r = results.get(f"case2_r{ri}_h{m}")
                if r:
                    cells.append(f"{r['e_lost_w']:.1f} | {-r['i_support']:.1f} | "
                                 f"{r.get('x_drift', float('nan')):.2e} | "
                                 f"{r.get('l_defect', float('nan')):.2e}")
                else:
                    cells.append("- | - | - | -")
            tables.setdefault("case2", {})["/".join(rule)] = [results.get(f"case2_r{ri}_h{m}")
                                                            for m in meshes]
            print(f"| {'/'.join(rule)} | " + " | ".join(cells) + " |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"tables": tables, "runs": results}, f, indent=1)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
