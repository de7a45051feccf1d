#!/usr/bin/env python3
"""Every plot script in plots/ warns when its output has nothing for it to draw, and only then.

The scripts are found by listing plots/: every *.py with a `__main__` block is a plot script
(spbread.py and _common.py are modules), and each must have a case below, so a new script
without one fails this test. For each script:

  * on an output with nothing for it to draw (no profiles, no fragment blocks, a bar that
    never breaks, no gauges, no x-t field and no events, a zero base reaction, no base impulse
    and no event loss in case 2's ensembles and rules (figures.py fig13), no fracture in a
    fragmentation window, an ensemble without rows in the time window), read from PREFIX.h5
    and from the text files alone: exit status 0, the line 'SCRIPT: warning: nothing to
    draw: ...' on stderr, and the PNG written;
  * on an output that has it: exit status 0, no warning on stderr, a PNG written.

usage: plots_nothing_to_draw.py SPALLBAR INPUT_DIR PLOTS_DIR WORKDIR   (a Python with numpy,
matplotlib, h5py: the project venv)
"""
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import time

from clitools import Checks, run

# a bar with free ends, no load, no gravity: no profiles, fragments, gauges, x-t field,
# events or base reaction
EMPTY = """&run
  title = 'nothing to draw'
  t_end = 1.0e-4
  hdf5 = .true.
  {extra}
/
&mesh
  cells = 10
/
&segments
  n = 1
  length = 1.0
  young = 1.0e9
  density = 1000.0
/
"""
# figures.py --only fig10 reads input/example3_case1_{accelerate,delay,fixed}.nml: here a
# bar hanging from a fixed top, whose free bottom never pushes on anything
HANGING = """&run
  title = 'hanging bar: no base reaction'
  t_end = 0.05
  gravity = 9.81
/
&mesh
  cells = 19
/
&segments
  n = 1
  length = 0.95
  young = 20.0e6
  density = 1765.8
/
&ends
  top = 'fixed'
  bottom = 'free'
/
&initial
  state = 'static'
/
"""
# figures.py --only fig13 reads input/example3_case2/accelerate_above_h19.nml (its ensembles
# perturb p0): here the bar of EMPTY under a pressure, with no base and no event
NO_BASE = EMPTY.format(extra="") + "&load\n  kind = 'power'\n  p0 = 1.0e6\n/\n"


def plot_scripts(plots):
    """The plot scripts of PLOTS: the *.py files that run as programs."""
    return sorted(f[:-3] for f in os.listdir(plots) if f.endswith(".py") and
                  re.search(r"^if __name__ == .__main__.:", open(os.path.join(plots, f)).read(),
                            re.M))


def png_ok(path):
    return os.path.exists(path) and os.path.getsize(path) > 1000 and \
        open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


def main():
    exe, indir, plots, work = (os.path.abspath(a) for a in sys.argv[1:5])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()

    def spallbar(name, text):
        with open(os.path.join(work, name + ".nml"), "w") as f:
            f.write(text)
        r = run(exe, [name + ".nml", "-q"], work)
        check(r.returncode == 0, f"spallbar {name}: exit {r.returncode} {r.stderr.strip()}")
        return os.path.join(work, name)

    # outputs with nothing to draw; the same from the text files alone
    empty = spallbar("empty", EMPTY.format(extra=""))
    intact = spallbar("intact", EMPTY.format(extra="profile_times = 5.0e-5, 1.0e-4"))
    empty_text = os.path.join(work, "empty_text")
    for ext in (".his", ".evt", ".prf", ".frg"):
        shutil.copy(empty + ext, empty_text + ext)
    hanging = os.path.join(work, "hanging_input")
    os.makedirs(hanging)
    for rule in ("accelerate", "delay", "fixed"):
        with open(os.path.join(hanging, f"example3_case1_{rule}.nml"), "w") as f:
            f.write(HANGING)
    os.makedirs(os.path.join(hanging, "example3_case2"))
    with open(os.path.join(hanging, "example3_case2", "accelerate_above_h19.nml"), "w") as f:
        f.write(NO_BASE)
    # outputs with something to draw: Example 2 for 1.2 ms (spall, collisions; x-t rows
    # every 4 steps, two gauges) and Example 3 case 1 for 0.1 s (base reaction)
    deck = open(os.path.join(indir, "example2.nml")).read()
    deck = deck.replace("&run", "&run\n  hdf5 = .true.\n  field_every = 4", 1)
    deck = deck.replace("t_end         = 2.0e-3", "t_end         = 1.2e-3")
    deck = deck.replace(", 1.4e-3, 1.6e-3, 1.8e-3, 2.0e-3", "")
    ex2 = spallbar("ex2", deck + "&gauges\n  x = 0.3, 1.0\n/\n")
    deck = open(os.path.join(indir, "example3_case1_accelerate.nml")).read()
    deck = re.sub(r"profile_times\s*=.*", "profile_times = 0.05", deck)
    ex3 = spallbar("ex3", deck.replace("t_end         = 1.0", "t_end         = 0.1"))
    # an ensemble (plots/ensemble.py): 3 realizations of the bar of EMPTY under a pressure
    ens_deck = NO_BASE + ("&sweep\n  perturb = 'p0'\n  realizations = 3\n"
                          "  ensemble_columns = 'e_kin'\n/\n")
    with open(os.path.join(work, "ens.nml"), "w") as f:
        f.write(ens_deck)
    r = run(exe, ["--sweep", "ens.nml", "-q"], work)
    check(r.returncode == 0, f"spallbar --sweep ens: exit {r.returncode} {r.stderr.strip()}")
    ens = os.path.join(work, "ens")
    # the spall test of input/ to 0.4 ms: a gauge on the rear face, its .spl row
    deck = open(os.path.join(indir, "spall_test.nml")).read()
    spall = spallbar("spall", deck.replace("t_end         = 6.0e-4", "t_end         = 4.0e-4"))
    # a striking mass on the bar of EMPTY: two blows' worth of contact
    struck = spallbar("struck", EMPTY.format(extra="") +
                      "&impactor\n  mass = 500.0\n  velocity = 2.0\n/\n")

    def out(name):
        return os.path.join(work, name + ".png")

    study = os.path.join(plots, "fragmentation_study.py")
    # script: ([(case, arguments, png)] with nothing to draw, (arguments, png) with something)
    cases = {
        "profiles": ([("h5", [empty], "p0"), ("text", [empty_text], "p1")], ([ex2], "p2")),
        "fragments": ([("h5", [empty], "f0"), ("text", [empty_text], "f1"),
                       ("one piece", [intact], "f3")], ([ex2], "f2")),
        "gauges": ([("h5", [empty], "g0"), ("text", [empty_text], "g1")], ([ex2], "g2")),
        "xt": ([("h5", [empty], "x0"), ("text", [empty_text], "x1")], ([ex2], "x2")),
        "reaction": ([("h5", [empty], "r0"), ("text", [empty_text], "r1")], ([ex3], "r2")),
        "blows": ([("h5", [empty], "b0"), ("text", [empty_text], "b1")], ([struck], "b2")),
        # an ensemble whose rows all lie before the time window
        "ensemble": ([("no row in the window", [ens, "--t-min", "1"], "e0")], ([ens], "e1")),
        # no gauge on an end (and, from the text files alone, no .spl either)
        "spall": ([("h5", [empty], "sp0"), ("text", [empty_text], "sp1")], ([spall], "sp2")),
        # the paper's Fig. 10 from decks whose bar never touches a base; Fig. 13 (case 2's
        # ensembles and rule band, 2 realizations per mesh) from a free bar: no base impulse,
        # no event loss; then both from input/
        "figures": ([("no base reaction", ["--exe", exe, "--input", hanging, "--out",
                                           os.path.join(work, "fig_none"), "--only", "fig10"],
                      os.path.join("fig_none", "fig10")),
                     ("no base impulse, no event loss",
                      ["--exe", exe, "--input", hanging, "--out", os.path.join(work, "fig13_none"),
                       "--only", "fig13", "--realizations", "2"],
                      os.path.join("fig13_none", "fig13"))],
                    (["--exe", exe, "--input", indir, "--out", os.path.join(work, "fig_some"),
                      "--only", "fig10", "fig13", "--realizations", "2"],
                     (os.path.join("fig_some", "fig10"), os.path.join("fig_some", "fig13")))),
        # 1e6 1/s: the study's run is one step long, too short for any fracture
        "fragmentation_study": (
            [("no fracture", ["--exe", exe, "--rates", "1e6", "--realizations", "1", "--out",
                              os.path.join(work, "study_none"), "--figure", out("s0")], "s0")],
            (["--exe", exe, "--rates", "100", "--realizations", "1", "--out",
              os.path.join(work, "study_some"), "--figure", out("s1")], "s1")),
        # the ZMR bar stopped long before its first crack; then one that breaks
        "zmr_study": (
            [("no fracture", ["--exe", exe, "--rates", "1", "--resolutions", "5",
                              "--realizations", "1", "--ranks", "1", "--duration", "0.01",
                              "--out", os.path.join(work, "zmr_none"), "--figure", out("z0")],
              "z0")],
            (["--exe", exe, "--rates", "10", "--resolutions", "5", "--realizations", "1",
              "--ranks", "1", "--out", os.path.join(work, "zmr_some"), "--figure", out("z1")],
             "z1")),
    }
    scripts = plot_scripts(plots)
    check(len(scripts) >= 8, f"plot scripts found in {plots}: {scripts}")
    for s in scripts:
        check(s in cases, f"plots/{s}.py has no case in {os.path.basename(__file__)}")
    for s in cases:
        check(s in scripts, f"case {s}: no plots/{s}.py (or it does not run as a program)")

    env = dict(os.environ, MPLBACKEND="Agg")

    def invoke(script, args, png):
        # the per-prefix scripts take PREFIX ... -o PNG; the others name their PNG themselves
        extra = ["-o", out(png)] if not args[0].startswith("--") else []
        start = time.monotonic()
        r = subprocess.run([sys.executable, os.path.join(plots, script + ".py")] + args
                              + extra, capture_output=True, text=True, env=env, cwd=work,
                              timeout=600, stdin=subprocess.DEVNULL)
        r.seconds = time.monotonic() - start
        return r

    jobs = []
    for s in scripts:
        if s not in cases:
            continue
        nothing, something = cases[s]
        for what, args, png in nothing:
            jobs.append((s, f"nothing to draw ({what})", args, png, True))
        jobs.append((s, "something to draw", something[0], something[1], False))
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        results = list(pool.map(lambda j: invoke(j[0], j[2], j[3]), jobs))
    for (s, what, args, png, warns), r in zip(jobs, results):
        name = f"{s}.py, {what}"
        line = f"{s}.py: warning: nothing to draw: "
        check(r.returncode == 0, f"{name}: exit {r.returncode} {r.stderr.strip()[-600:]}")
        for one in (png if isinstance(png, tuple) else (png,)):
            check(png_ok(out(one)), f"{name}: no PNG {out(one)}")
        if warns:
            check(any(ln.startswith(line) for ln in r.stderr.splitlines()),
                  f"{name}: no '{line}...' line on stderr: {r.stderr.strip()[-600:]!r}")
        else:
            check("warning" not in r.stderr.lower(),
                  f"{name}: a warning on stderr: {r.stderr.strip()[-600:]!r}")
        print(f"{name}: exit {r.returncode}, {r.seconds:.1f} s; " + (" | ".join(
            ln for ln in r.stderr.splitlines() if "nothing to draw" in ln) or "no warning"))
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
