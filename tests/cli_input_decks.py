#!/usr/bin/env python3
"""Every deck in input/ runs (exit 0) and its outputs keep the contract of doc/outputs.md:
the history's last header line names the required columns, rows are numbers, the energy
ledger is constant, profiles come in '# t = ' blocks of 2N rows.

usage: cli_input_decks.py SPALLBAR INPUT_DIR WORKDIR
"""
import glob
import os
import shutil
import sys

from clitools import Checks, run

REQUIRED = ["t", "reaction_bottom", "reaction_top", "fragments", "e_kin", "e_strain",
            "e_pot", "w_ext", "e_lost", "momentum"]


def read_table(path):
    header, rows = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header.append(line)
            elif line.startswith(" "):      # not the column-name first line
                rows.append([float(x) for x in line.split()])
    return header, rows


def main():
    exe, indir, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()

    decks = sorted(glob.glob(os.path.join(indir, "*.nml")))
    check(len(decks) > 0, "input/ has decks")
    for deck in decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        prefix = os.path.join(work, name)
        r = run(exe, [os.path.basename(deck), "--output", prefix], indir)
        check(r.returncode == 0, f"{name}: exit {r.returncode}: {r.stderr}")
        if r.returncode != 0:
            continue
        header, rows = read_table(prefix + ".his")
        cols = header[-1][1:].split()
        check(cols[:len(REQUIRED)] == REQUIRED, f"{name}: columns {cols}")
        check(len(rows) > 1 and all(len(x) == len(cols) for x in rows), f"{name}: row widths")
        ledger = [x[cols.index("ledger")] for x in rows]
        scale = max(max(abs(x[cols.index(c)]) for x in rows)
                    for c in ("e_kin", "e_strain", "e_pot", "w_ext"))
        drift = max(abs(v - ledger[0]) for v in ledger) / scale
        check(drift < 1e-9, f"{name}: ledger drift {drift:.3e} of the largest energy term")
        check(any("&segments" in h for h in header), f"{name}: deck echoed in header")
        # profiles: blocks of 2N rows
        nodes = None
        for h in header:
            if h.startswith("# mesh:"):
                nodes = int(h.split(",")[1].split()[0])
        with open(prefix + ".prf") as f:
            lines = f.read().splitlines()
        starts = [i for i, l in enumerate(lines) if l.startswith("# t = ")]
        for i in starts:
            block = []
            for l in lines[i + 1:]:
                if l.startswith("# t = "):
                    break
                if l.startswith(" "):
                    block.append(l)
            check(len(block) == 2 * nodes, f"{name}: profile block of {len(block)} rows, expected {2 * nodes}")
        # fragments: one block per profile; each block lists as many fragments as the
        # history's 'fragments' column says at that time; masses add up to the bar's
        fh, frows = read_table(prefix + ".frg")
        fcols = [h for h in fh if h.startswith("# id ")][0][1:].split()
        with open(prefix + ".frg") as f:
            blocks = [l for l in f if l.startswith("# t = ")]
        check(len(blocks) == len(starts), f"{name}: {len(blocks)} fragment blocks, {len(starts)} profiles")
        masses = {}
        with open(prefix + ".frg") as f:
            t = None
            for l in f:
                if l.startswith("# t = "):
                    t = l
                    masses[t] = 0.0
                elif l.startswith(" ") and l.strip():
                    masses[t] += float(l.split()[fcols.index("mass")])
        check(len(set(round(m, 9) for m in masses.values())) <= 1, f"{name}: fragment mass changes {masses}")
        with open(prefix + ".evt") as f:
            ev = [l.split() for l in f if l.startswith(" ") and l.strip()]
        ecols = [l for l in open(prefix + ".evt") if l.startswith("#")][-1][1:].split()
        check(ecols[:6] == ["t", "step", "kind", "node", "x", "stress"], f"{name}: event columns {ecols}")
        check(all(len(e) == len(ecols) for e in ev), f"{name}: event row widths")
        frag_col = [x[cols.index("fragments")] for x in rows]
        # pieces: +1 per fracture or separation between pieces, -1 per collision between
        # pieces; events at the base (base-collision, separation at the bottom node) do not
        # change the count
        nodes = int([h for h in header if h.startswith("# mesh:")][0].split(",")[1].split()[0])
        opened = sum(1 for e in ev if e[2] in ("fracture", "separation") and int(e[3]) != nodes)
        closed = sum(1 for e in ev if e[2] == "collision")
        check(frag_col[-1] == 1 + opened - closed,
              f"{name}: {frag_col[-1]} fragments after {opened} openings and {closed} collisions")
        print(f"ok   {name}: {len(rows)} history rows, {len(starts)} profiles, {len(ev)} events, "
              f"ledger drift {drift:.2e}")
    # paths in a deck are relative to its folder (doc/deck.md, "Paths in a deck"): example1's
    # load table is found when the deck is run from elsewhere, and the results are the same
    # numbers
    elsewhere = os.path.join(work, "elsewhere")
    os.makedirs(elsewhere)
    r = run(exe, [os.path.join(os.path.abspath(indir), "example1.nml"), "--output", "ex1",
                  "--quiet"], elsewhere)
    check(r.returncode == 0, f"example1 run from another folder: exit {r.returncode} {r.stderr}")
    if r.returncode == 0:
        _, here = read_table(os.path.join(elsewhere, "ex1.his"))
        _, there = read_table(os.path.join(work, "example1.his"))
        check(here == there, "example1 run from another folder: other numbers")
        print("ok   example1.nml run from another folder finds its table: the same history")
    # the end-of-run summary (issue 21): events by kind, the fragments at the end, every file
    r = run(exe, ["example2.nml", "--output", os.path.join(work, "sum2")], indir)
    out = r.stdout
    frag = [l for l in out.splitlines() if l.startswith("    ") and ": x = " in l]
    check(r.returncode == 0 and "events: 12 (fractures 4, collisions 4, separations 4, " in out
          and "fractures: 4 (time, place, section stress" in out
          and "    t =  4.3200E-04 s at x =  1.9600E-01 m, stress -1.2240E+06 Pa" in out
          and len([l for l in out.splitlines() if l.startswith("    t = ")]) == 4
          and "fragments at the end: 5 (" in out and len(frag) == 5
          and "length  1.600E+00 m" in frag[-1] and ("wrote " + os.path.join(work, "sum2") +
                                                     ".his") in out,
          f"example2's summary: {out}")
    print("ok   example2's summary lists events by kind, 5 fragments and the files written")
    # more fractures than the summary lists: the first five, and how many more (the .evt's
    # first five fracture rows, the count from it)
    deck = os.path.join("example3_case2", "accelerate_above_h19.nml")
    r = run(exe, [deck, "--output", os.path.join(work, "sum3")], indir)
    with open(os.path.join(work, "sum3.evt")) as f:
        fr = [l.split() for l in f if l.startswith(" ") and l.split()[2] == "fracture"]
    listed = [l for l in r.stdout.splitlines() if l.startswith("    t = ")]
    check(r.returncode == 0 and len(fr) > 5 and len(listed) == 5
          and all(abs(float(l.split()[2]) - float(e[0])) <= 1e-4 * float(e[0]) and
                  abs(float(l.split()[7]) - float(e[4])) <= 1e-4 * abs(float(e[4])) + 1e-12
                  for l, e in zip(listed, fr))
          and f"    ... and {len(fr) - 5} more (" in r.stdout,
          f"case 2's summary: {len(fr)} fractures in the .evt; listed {listed}\n{r.stdout}")
    print("ok   case 2's summary lists the first 5 fractures as in the .evt, and the count of the rest")
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
