#!/usr/bin/env python3
"""Command-line contract for bad input (doc/deck.md; README.md, "The command line"): exit status 2,
exactly one line on stderr naming the group and variable, and no output file written or
touched.

usage: cli_deck_errors.py SPALLBAR WORKDIR
"""
import os
import re
import shutil
import sys

from clitools import Checks, run

GOOD = """&run t_end = 1.0e-5, title = 'cli' /
&mesh cells = 10 /
&segments n = 1, length = 0.05, young = 200e9, density = 8000 /
&load kind = 'power', p0 = 1e6 /
"""

# two bonded segments of the areas AREA, a pressure on the wide top (issue 32, item 7)
AREAS = """&run t_end = 4e-4, history_every = 1 /
&mesh cells = 40 /
&segments n = 2, length = 0.5, 0.5, young = 2e11, 2e11, density = 7800, 7800, area = AREA /
&load kind = 'power', p0 = 1e8, exponent = 0 /
"""

# (name, deck text, text the single stderr line must contain)
BAD = [
    ("no_run", "&mesh cells = 10 /\n", "spallbar: &run: required group is missing"),
    ("neg_length", GOOD.replace("length = 0.05", "length = -0.5"),
     "spallbar: &segments: length(1) must be > 0, got -0.5"),
    ("unknown_var", GOOD.replace("cells = 10", "cells = 10, celz = 3"),
     "spallbar: &mesh: celz: unknown variable"),
    ("unknown_group", GOOD + "&gizmo a = 1 /\n", "spallbar: &gizmo: unknown group"),
    ("nan", GOOD.replace("t_end = 1.0e-5", "t_end = NaN"), "spallbar: &run: t_end must be a finite"),
    ("inf", GOOD.replace("young = 200e9", "young = Inf"), "spallbar: &segments: young(1) must be a finite"),
    ("bad_choice", GOOD + "&ends top = 'glued' /\n", "spallbar: &ends: top must be"),
    # cohesive cracks (issue 31): Gc needs a strength to open at, a breakable segment, the
    # half-mass model, and is not negative
    ("gc_no_strength", GOOD.replace("density = 8000", "density = 8000, strength = 0, fracture_energy = 100"),
     "spallbar: &segments: fracture_energy(1) > 0 needs strength(1) > 0"),
    ("gc_unbreakable", GOOD.replace("density = 8000", "density = 8000, fracture_energy = 100"),
     "spallbar: &segments: fracture_energy(1) > 0 needs strength(1) >= 0"),
    ("gc_negative", GOOD.replace("density = 8000", "density = 8000, strength = 1e6, fracture_energy = -1"),
     "spallbar: &segments: fracture_energy(1) must be"),
    ("gc_full_mass", GOOD.replace("density = 8000", "density = 8000, strength = 1e6, fracture_energy = 10")
     .replace("title = 'cli'", "title = 'cli', model = 'full-mass'"),
     "spallbar: &segments: fracture_energy > 0 needs &run model = 'half-mass'"),
    ("strict_fit", GOOD.replace("n = 1, length = 0.05, young = 200e9, density = 8000",
                                "n = 2, length = 0.05, 0.0512, young = 2*200e9, density = 2*8000"),
     "spallbar: &segments: length(2)"),
    # a string names its variable and closes on its own line: the quote that would close
    # it later belongs to another value (issue 19)
    ("unterminated", GOOD.replace("title = 'cli'", "title = 'cli"),
     "spallbar: &run: title: unterminated string starting at line 1"),
    ("unterminated_later", GOOD.replace("kind = 'power'", "kind = 'power"),
     "spallbar: &load: kind: unterminated string starting at line 4"),
    ("tab_in_string", GOOD.replace("title = 'cli'", "title = 'c\tli'"),
     "spallbar: &run: title: character code 9 in a string (line 1)"),
    ("bel_in_string", GOOD.replace("kind = 'power'", "kind = 'pow\x07er'"),
     "spallbar: &load: kind: character code 7 in a string (line 4)"),
    ("unused_missing_table", GOOD.replace("p0 = 1e6", "p0 = 1e6, table = 'nope.txt'"),
     "spallbar: &load: table = 'nope.txt': cannot open"),
    ("missing_table", GOOD.replace("kind = 'power', p0 = 1e6", "kind = 'table', table = 'nope.txt'"),
     "spallbar: &load: table = 'nope.txt': cannot open"),
    ("binary", "&run t_end = 1 \x01\x02 /\n", "spallbar: &run: line 1: character code 1"),
    ("wrong_type", GOOD.replace("cells = 10", "cells = 'ten'"), "spallbar: &mesh: cells: cannot read the value 'ten'"),
    # the one reader (issue 18) reads each assignment by itself: a word where a value should
    # be is refused (gfortran's whole-group read kept the default and exited 0)
    ("name_as_value", GOOD.replace("title = 'cli'", "title = 'cli', timing = timing"),
     "spallbar: &run: timing: cannot read the value 'timing'"),
    ("word_after_value", GOOD.replace("t_end = 1.0e-5,", "t_end = 1.0e-5 gravity,"),
     "spallbar: &run: t_end: cannot read the value '1.0e-5 gravity'"),
    ("component", GOOD.replace("title = 'cli'", "title = 'cli', t_end%x = 1"),
     "spallbar: &run: t_end%x: unknown variable in this group"),
    ("stray_word", GOOD.replace("&mesh cells = 10", "&mesh ten cells = 10"),
     "spallbar: &mesh: cannot read the value 'ten'"),
    # issue 32, item 9: the message names the real cause ("x is required" before)
    ("gauge_101", GOOD + "&gauges x(101) = 0.05 /\n", "spallbar: &gauges: x(101): at most 100 gauges"),
    ("gauge_gap", GOOD + "&gauges x(3) = 0.01 /\n",
     "spallbar: &gauges: x(3) is given but x(1) is not"),
    # issue 32, item 7: axial impedances rho a A more than 1e6 apart (the deck ran
    # into the energy guard, exit 3, at 1e30; at 1e20 its wave ledger drifted)
    ("area_ratio", AREAS.replace("AREA", "1e30, 1"),
     "spallbar: &segments: area(2): the axial impedance rho a A of segment 1 is 1e30 times "
     "that of segment 2; at most 1e6 is supported"),
    ("area_ratio_small_areas", AREAS.replace("AREA", "2e-4, 2e-11"),
     "spallbar: &segments: area(2): the axial impedance rho a A of segment 1 is 1e7 times"),
    ("impedance_ratio", AREAS.replace("AREA", "1, 1").replace("density = 7800, 7800",
                                                              "density = 7800, 7.8e-27")
     .replace("young = 2e11, 2e11", "young = 2e11, 2e-19"),
     "spallbar: &segments: young(2), density(2): the axial impedance rho a A of segment 1 "
     "is 1e30 times that of segment 2"),
]


def read_as_nothing(exe, work, check):
    """Issue 32, item 9: a deck or a load table that starts with a UTF-8 byte-order mark (an
    editor on Windows writes one) runs as without it ("text outside any &group" before); a
    table line holding only a tab (or a CR) is blank like an empty line (refused before)."""
    bom = b"\xef\xbb\xbf"
    with open(os.path.join(work, "plain.nml"), "w") as f:
        f.write(GOOD)
    with open(os.path.join(work, "bom.nml"), "wb") as f:
        f.write(bom + GOOD.encode())
    for name in ("plain", "bom"):
        r = run(exe, [name + ".nml", "--quiet"], work)
        check(r.returncode == 0 and not r.stderr, f"{name} deck: exit {r.returncode} {r.stderr!r}")
    rows = [[l for l in open(os.path.join(work, n + ".his")) if not l.startswith(("#", "t "))]
            for n in ("plain", "bom")]
    check(rows[0] == rows[1] and rows[0], "a deck with a BOM: other rows than without")
    table = "0 0\n1e-6 1e6\n1e-5 1e6\n"
    for name, data in (("tplain", table.encode()), ("tbom", bom + table.encode()),
                       ("ttab", b"0 0\n\t\n1e-6\t1e6\r\n \t \n1e-5 1e6\n")):
        with open(os.path.join(work, name + ".txt"), "wb") as f:
            f.write(data)
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(GOOD.replace("&load kind = 'power', p0 = 1e6 /",
                                 f"&load kind = 'table', table = '{name}.txt' /"))
        r = run(exe, [name + ".nml", "--quiet"], work)
        check(r.returncode == 0 and not r.stderr, f"table {name}: exit {r.returncode} {r.stderr!r}")
    rows = [[l for l in open(os.path.join(work, n + ".his")) if not l.startswith(("#", "t "))]
            for n in ("tplain", "tbom", "ttab")]
    check(rows[0] and rows[0] == rows[1] == rows[2], "tables with a BOM, tabs, CRs: other rows")
    print("ok   a BOM in a deck or table, a table line of a tab: read as nothing")


def deck_help_matches_doc(exe, work, check):
    """spallbar --deck-help (the variable table of spb_deck_params) and doc/deck.md list the
    same variables group by group, and the doc names every value a keyword accepts."""
    r = run(exe, ["--deck-help"], work)
    check(r.returncode == 0, f"--deck-help: exit {r.returncode}")
    listed, group = {}, None
    for line in r.stdout.splitlines():
        if line.startswith("&"):
            group = line[1:].strip()
        elif line.startswith("   ") and group:
            name, rest = line.strip().split("=", 1)
            listed[(group, name.strip())] = re.findall(r"'([a-z-]+)'", rest.split("(", 1)[-1]) \
                if "|" in rest else []
    doc = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "doc",
                            "deck.md"), encoding="utf-8").read()
    rows, group = {}, None
    for line in doc.splitlines():
        m = re.match(r"## &(\w+)", line)
        if m:
            group = m.group(1)
        m = re.match(r"\| `(\w+)(?:\(j\))?` \|", line)
        if m and group:
            rows[(group, m.group(1))] = line
    check(len(listed) > 40, f"--deck-help lists {len(listed)} variables")
    for key, choices in listed.items():
        check(key in rows, f"--deck-help lists &{key[0]} {key[1]}, doc/deck.md has no row for it")
        for c in choices:
            check(key not in rows or f"'{c}'" in rows[key],
                  f"doc/deck.md: &{key[0]} {key[1]} does not name the choice '{c}'")
    for key in rows:
        check(key in listed, f"doc/deck.md documents &{key[0]} {key[1]}, which no deck reads")
    print(f"ok   --deck-help and doc/deck.md: {len(listed)} variables, "
          f"{sum(len(c) for c in listed.values())} choices")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()

    for name, text, expect in BAD:
        deck = os.path.join(work, name + ".nml")
        with open(deck, "w", encoding="latin-1") as f:
            f.write(text)
        # an older result with the same prefix must survive a rejected deck untouched
        old = os.path.join(work, name + ".his")
        with open(old, "w") as f:
            f.write("old result\n")
        r = run(exe, [name + ".nml"], work)
        lines = r.stderr.splitlines()
        check(r.returncode == 2, f"{name}: exit status {r.returncode}, expected 2")
        check(len(lines) == 1, f"{name}: {len(lines)} stderr lines: {r.stderr!r}")
        check(len(lines) >= 1 and expect in lines[0], f"{name}: stderr {r.stderr!r} lacks {expect!r}")
        check(open(old).read() == "old result\n", f"{name}: an existing output was touched")
        for ext in (".prf", ".evt", ".frg", ".h5"):
            check(not os.path.exists(os.path.join(work, name + ext)), f"{name}: left {name}{ext}")
        print(f"ok   {name}: {lines[0] if lines else ''}")

    # a sweep that varies an area beyond the ratio is refused before any case runs
    with open(os.path.join(work, "sweep_area.nml"), "w") as f:
        f.write(AREAS.replace("AREA", "1, 1") + "&sweep vary = 'area(1)', values = 1e3, 1e30 /\n")
    r = run(exe, ["--sweep", "sweep_area.nml", "--quiet"], work)
    expect = ("spallbar: &sweep: values(2) = 1e30 for area(1): &segments: area(2): the axial "
              "impedance rho a A of segment 1 is 1e30 times that of segment 2")
    check(r.returncode == 2 and len(r.stderr.splitlines()) == 1 and expect in r.stderr,
          f"sweep over area: exit {r.returncode}, stderr {r.stderr!r}")
    left = [x for x in os.listdir(work) if x.startswith("sweep_area") and x != "sweep_area.nml"]
    check(not left, f"sweep over area: wrote {left}")

    # command line itself
    for args, expect in ((["missing.nml"], "spallbar: deck: cannot open"),
                         ([], "spallbar: command line: no deck given"),
                         (["--frobnicate", "x.nml"], "unknown option"),
                         (["a.nml", "b.nml"], "more than one deck"),
                         (["--output"], "--output needs a PREFIX")):
        r = run(exe, args, work)
        check(r.returncode == 2, f"{args}: exit {r.returncode}")
        check(expect in r.stderr and len(r.stderr.splitlines()) == 1, f"{args}: stderr {r.stderr!r}")
    r = run(exe, ["--help"], work)
    check(r.returncode == 0 and "usage" in r.stdout, "--help")
    deck_help_matches_doc(exe, work, check)
    read_as_nothing(exe, work, check)

    # a good deck runs, writes the three files, and --output chooses the prefix
    with open(os.path.join(work, "good.nml"), "w") as f:
        f.write(GOOD)
    r = run(exe, ["good.nml", "--output", "out/run1", "--quiet"], work)
    check(r.returncode == 2 and "--output: cannot write" in r.stderr,
          f"output into a missing folder: {r.returncode} {r.stderr!r}")
    os.makedirs(os.path.join(work, "out"))
    r = run(exe, ["good.nml", "--output", "out/run1", "--quiet"], work)
    check(r.returncode == 0, f"good deck: exit {r.returncode}: {r.stderr}")
    check(r.stdout == "" and r.stderr == "", "--quiet prints nothing")
    for ext in (".his", ".prf", ".evt", ".frg"):
        check(os.path.exists(os.path.join(work, "out", "run1" + ext)), f"good deck wrote {ext}")
    r = run(exe, ["good.nml"], work)
    check(r.returncode == 0 and os.path.exists(os.path.join(work, "good.his")), "default prefix")

    # a group's name inside a string is text: &mesh is read from the group, not the title
    with open(os.path.join(work, "title.nml"), "w") as f:
        f.write(GOOD.replace("title = 'cli'", "title = 'see &mesh cells = 3 /'"))
    r = run(exe, ["title.nml", "--quiet"], work)
    his = open(os.path.join(work, "title.his")).read() if r.returncode == 0 else ""
    check(re.search(r"cells += 10 +! input", his) is not None,
          f"&mesh inside a string: exit {r.returncode}, echo of cells: "
          f"{re.findall(r'cells += .*', his)}")

    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
