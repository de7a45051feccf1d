#!/usr/bin/env python3
"""The plot scripts' options (issue 35; doc/outputs.md, "Plots"), on the paper's Example 2
(x-t field, events, profiles, fragments, two gauges), a striking mass's run and the spall
test of input/ (spall.py):

  * the per-run scripts (every script of plots/ that takes PREFIX ... -o PNG) accept
    --t-min/--t-max (seconds or with a unit), --units (s, ms, us, µs; Pa, kPa, MPa, GPa),
    gauges.py --gauges: exit 0 and a PNG; drawn in-process, what they draw lies in the
    window, in the units asked for, only the gauges asked for;
  * without --units every script's time is in ms (one default for all);
  * a missing output (no PREFIX.h5 and no PREFIX.his), a damaged PREFIX.h5, a text run
    without its PREFIX.evt, a PNG that cannot be written: exit 2 and exactly one line
    'SCRIPT.py: error: ...' on stderr, no traceback; a bad option value: exit 2;
  * PREFIX.h5 given for PREFIX is read as the run (ensemble.py: a sweep's PREFIX_sweep.h5).

usage: plots_options.py SPALLBAR INPUT_DIR PLOTS_DIR WORKDIR   (a Python with numpy,
matplotlib, h5py: the project venv)
"""
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys

from clitools import Checks, run_decks

WINDOW = ["--t-min", "0.2ms", "--t-max", "9e-4"]       # [2e-4 s, 9e-4 s]
T_MIN, T_MAX = 2.0e-4, 9.0e-4
STRUCK = """&run
  title = 'a mass strikes a free bar'
  t_end = 1.0e-3
  hdf5 = .true.
/
&mesh cells = 20 /
&segments n = 1, length = 1.0, young = 1.0e9, density = 1000.0 /
&impactor mass = 500.0, velocity = 2.0 /
"""


# an ensemble (plots/ensemble.py): a bar struck by a pressure p0 perturbed by 1e-3, 4
# realizations, to 1 ms (the window above lies in it)
ENSEMBLE = """&run
  title = 'an ensemble'
  t_end = 1.0e-3
/
&mesh cells = 20 /
&segments n = 1, length = 1.0, young = 1.0e9, density = 1000.0, strength = 1.0e6 /
&ends bottom = 'fixed' /
&load kind = 'power', p0 = 2.0e6, t_k = 2.0e-4, exponent = 1.0 /
&sweep perturb = 'p0', realizations = 4, ensemble_columns = 'reaction_bottom', 'e_kin' /
"""


def ensemble(check, exe, work):
    """The sweep of ENSEMBLE in WORK; its prefix."""
    with open(os.path.join(work, "ens.nml"), "w") as f:
        f.write(ENSEMBLE)
    r = subprocess.run([exe, "--sweep", "ens.nml", "-q"], cwd=work, capture_output=True,
                       text=True, timeout=600, stdin=subprocess.DEVNULL)
    check(r.returncode == 0, f"spallbar --sweep ens.nml: exit {r.returncode}: {r.stderr}")
    return os.path.join(work, "ens")


def per_run_scripts(plots):
    """The scripts that draw given runs: they take PREFIX ... -o PNG (their parser is
    _common.parser)."""
    return sorted(f[:-3] for f in os.listdir(plots) if f.endswith(".py") and
                  re.search(r"^if __name__ == .__main__.:", text(plots, f), re.M) and
                  re.search(r"\bparse\(parser\(", text(plots, f)))


def text(folder, name):
    with open(os.path.join(folder, name)) as f:
        return f.read()


def png_ok(path):
    return os.path.exists(path) and os.path.getsize(path) > 1000 and \
        open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


def in_process(check, plots, ex2, struck, ens, spall_run):
    """Draw with the scripts' plot functions and look at what they drew."""
    sys.path.insert(0, plots)
    import numpy as np
    from matplotlib.collections import PathCollection
    import _common
    import blows
    import ensemble
    import fragments
    import gauges
    import profiles
    import reaction
    import spall
    import xt
    plt = _common.plt
    runs = {"ex2": _common.load(ex2), "struck": _common.load(struck),
            "spall": _common.load(spall_run)}
    view = _common.View(time="us", stress="kPa", t_min=T_MIN, t_max=T_MAX, gauges=[2])
    lo, hi = T_MIN * 1e6, T_MAX * 1e6

    def xs_in_window(lines, what):
        xs = np.concatenate([np.asarray(ln.get_xdata(), float) for ln in lines] or [[]])
        check(len(xs) > 0 and xs.min() >= lo * (1 - 1e-12) and xs.max() <= hi * (1 + 1e-12),
              f"{what}: times in [{lo:g}, {hi:g}] us: {xs.min() if len(xs) else None} .. "
              f"{xs.max() if len(xs) else None}")

    check(_common.DEFAULT_TIME_UNIT == "ms", "one default time unit: ms")
    # gauges: gauge 2 only, in us and kPa
    fig, axes = plt.subplots(3, 1)
    n = gauges.plot([runs["ex2"]], ["ex2"], axes, view)
    g = runs["ex2"].gauges
    rows = (g["t"] >= T_MIN) & (g["t"] <= T_MAX)
    check(n == 1 and all(len(ax.lines) == 1 for ax in axes), f"gauges: one gauge drawn ({n})")
    check(np.allclose(axes[0].lines[0].get_ydata(), g["stress"][rows, 1] / 1e3, rtol=0,
                      atol=0), "gauges: gauge 2's stress in kPa")
    check("gauge 2" in axes[0].lines[0].get_label(), "gauges: labelled gauge 2")
    check(axes[-1].get_xlabel() == "t [µs]" and "[kPa]" in axes[0].get_ylabel(),
          f"gauges: axis labels {axes[-1].get_xlabel()!r}, {axes[0].get_ylabel()!r}")
    check(np.allclose(axes[-1].get_xlim(), (lo, hi), rtol=1e-12, atol=0),
          f"gauges: x limits {axes[-1].get_xlim()}")
    xs_in_window(axes[0].lines, "gauges")
    plt.close(fig)
    # reaction and blows: history rows in the window
    for module, run_name, n_axes in ((reaction, "ex2", 1), (blows, "struck", 2)):
        fig, axes = plt.subplots(n_axes, 1)
        axes = np.atleast_1d(axes)
        if module is reaction:
            module.plot([runs[run_name]], [run_name], axes[0], view=view)
        else:
            module.plot([runs[run_name]], [run_name], axes, view)
        name = module.__name__
        check(axes[-1].get_xlabel() == "t [µs]", f"{name}: x label {axes[-1].get_xlabel()!r}")
        xs_in_window([ln for ln in axes[0].lines if len(ln.get_xdata()) > 1], name)
        unit = "kPa"        # the struck bar's area is 1: f_impactor is a stress
        check(f"[{unit}]" in axes[0].get_ylabel(), f"{name}: y label {axes[0].get_ylabel()!r}")
        plt.close(fig)
    # ensemble: its rows in the window, the reaction's mean in kPa, e_kin in its own unit
    e = ensemble.load(ens)
    fig, axes = plt.subplots(2, 1)
    ensemble.plot([e], ["ens"], axes, view)
    rows = (e.t >= T_MIN) & (e.t <= T_MAX)
    xs_in_window(axes[0].lines, "ensemble")
    check(np.allclose(axes[0].lines[0].get_ydata(), e.stats["reaction_bottom"]["mean"][rows]
                      / 1e3, rtol=0, atol=0), "ensemble: the reaction's mean in kPa")
    check("[kPa]" in axes[0].get_ylabel() and "[J/m^2]" in axes[1].get_ylabel() and
          axes[-1].get_xlabel() == "t [µs]", f"ensemble: labels {axes[0].get_ylabel()!r} "
          f"{axes[1].get_ylabel()!r} {axes[-1].get_xlabel()!r}")
    plt.close(fig)
    # x-t: field rows and events in the window, the time axis in us
    fig, ax = plt.subplots()
    xt.plot(runs["ex2"], ax, view)
    ts = np.concatenate([np.asarray(c.get_offsets())[:, 1] for c in ax.collections
                         if isinstance(c, PathCollection)] or [[]])
    ev = runs["ex2"].events["t"]
    inside = int(((ev >= T_MIN) & (ev <= T_MAX)).sum())
    check(len(ts) == inside and inside < len(ev) and ts.min() >= lo and ts.max() <= hi,
          f"xt: the {inside} of {len(ev)} events in the window drawn ({len(ts)})")
    check(ax.get_ylabel() == "t [µs]" and np.allclose(ax.get_ylim(), (lo, hi), rtol=1e-12,
                                                       atol=0),
          f"xt: {ax.get_ylabel()!r} {ax.get_ylim()}")
    check(any("[kPa]" in a.get_ylabel() for a in fig.axes), "xt: colour bar in kPa")
    plt.close(fig)
    # profiles and fragment blocks: those in the window, their times in us
    for module in (profiles, fragments):
        fig, ax = plt.subplots()
        if module is profiles:
            module.plot(runs["ex2"], ax, view=view)
            times = [p["t"] for p in runs["ex2"].profiles]
        else:
            module.plot(runs["ex2"], ax, view)
            times = [b["t"] for b in runs["ex2"].fragments]
        want = [f"t = {t * 1e6:.4g} µs" for t in times if T_MIN <= t <= T_MAX]
        got = [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else []
        check(len(want) > 0 and len(want) < len(times) and
              [g.split(",")[0] for g in got] == want,
              f"{module.__name__}: legend {got} for {want}")
        plt.close(fig)
    # spall: the rear face's velocity in the window, in us, its peak and pull-back marked
    fig, ax = plt.subplots()
    n = spall.plot([runs["spall"]], ["spall"], ax, view)
    curves = [ln for ln in ax.lines if len(ln.get_xdata()) > 1 and
              not ln.get_label().startswith("_")]         # not the axhline of v = 0
    marks = [ln.get_label() for ln in ax.lines if len(ln.get_xdata()) == 1]
    check(n == 1 and ax.get_xlabel() == "t [µs]" and
          any("peak" in m for m in marks) and any("pull-back" in m for m in marks),
          f"spall: one end drawn ({n}), {ax.get_xlabel()!r}, marks {marks}")
    xs_in_window(curves, "spall")
    plt.close(fig)
    # the default: ms everywhere
    default = _common.View()
    labels = {}
    fig, axes = plt.subplots(3, 1)
    gauges.plot([runs["ex2"]], ["ex2"], axes, default)
    labels["gauges"] = axes[-1].get_xlabel()
    fig, ax = plt.subplots()
    reaction.plot([runs["ex2"]], ["ex2"], ax, view=default)
    labels["reaction"] = ax.get_xlabel()
    fig, axes = plt.subplots(2, 1)
    blows.plot([runs["struck"]], ["struck"], axes, default)
    labels["blows"] = axes[-1].get_xlabel()
    fig, ax = plt.subplots()
    xt.plot(runs["ex2"], ax, default)
    labels["xt"] = ax.get_ylabel()
    fig, ax = plt.subplots()
    profiles.plot(runs["ex2"], ax, view=default)
    labels["profiles"] = ax.get_legend().get_texts()[0].get_text()
    fig, ax = plt.subplots()
    fragments.plot(runs["ex2"], ax, default)
    labels["fragments"] = ax.get_legend().get_texts()[0].get_text()
    fig, ax = plt.subplots()
    spall.plot([runs["spall"]], ["spall"], ax, default)
    labels["spall"] = ax.get_xlabel()
    plt.close("all")
    check(all("ms" in v and "µs" not in v for v in labels.values()),
          f"the default time unit of every script is ms: {labels}")
    print(f"default time labels: {labels}")


def main():
    exe, indir, plots, work = (os.path.abspath(a) for a in sys.argv[1:5])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    check = Checks()
    deck = text(indir, "example2.nml")
    deck = deck.replace("&run", "&run\n  hdf5 = .true.\n  field_every = 4", 1)
    deck = deck.replace("t_end         = 2.0e-3", "t_end         = 1.2e-3")
    deck = deck.replace(", 1.4e-3, 1.6e-3, 1.8e-3, 2.0e-3", "")
    # the spall test of input/ (a gauge on the rear face): its pull-back lies in the window
    spall_deck = text(indir, "spall_test.nml").replace("t_end         = 6.0e-4",
                                                       "t_end         = 4.0e-4")
    spall_deck = spall_deck.replace("&run", "&run\n  hdf5 = .true.", 1)
    if not run_decks(check, exe, work, (("ex2", deck + "&gauges\n  x = 0.3, 1.0\n/\n"),
                                        ("struck", STRUCK), ("spall", spall_deck))):
        return check.finish()
    ex2, struck = os.path.join(work, "ex2"), os.path.join(work, "struck")
    ens = ensemble(check, exe, work)
    spall_run = os.path.join(work, "spall")
    # a text run without its .evt, a damaged PREFIX.h5
    for ext in (".his", ".prf", ".frg"):
        shutil.copy(ex2 + ext, os.path.join(work, "no_evt" + ext))
    with open(os.path.join(work, "damaged.h5"), "w") as f:
        f.write("not an HDF5 file\n")

    scripts = per_run_scripts(plots)
    check(set(scripts) >= {"profiles", "fragments", "gauges", "xt", "reaction", "blows"},
          f"per-run scripts found: {scripts}")
    env = dict(os.environ, MPLBACKEND="Agg")

    def invoke(job):
        script, args = job[0], job[2]
        return subprocess.run([sys.executable, os.path.join(plots, script + ".py")] + args,
                              capture_output=True, text=True, env=env, cwd=work, timeout=600,
                              stdin=subprocess.DEVNULL)

    def png(name):
        return os.path.join(work, name + ".png")

    jobs = []   # (script, what, args, expected exit, PNG or error words)
    for s in scripts:
        prefix = {"blows": struck, "ensemble": ens, "spall": spall_run}.get(s, ex2)
        extra = ["--gauges", "2"] if s == "gauges" else []
        # ensemble.py draws a sweep's ensemble: PREFIX_sweep.h5 or PREFIX.ens
        h5 = prefix + ("_sweep.h5" if s == "ensemble" else ".h5")
        missing = ["no run output", "nothing_here.h5", "nothing_here.his"]
        if s == "ensemble":
            missing = ["no ensemble output", "nothing_here_sweep.h5", "nothing_here.ens"]
        jobs += [
            (s, "window, us and kPa", [prefix, "-o", png(s + "_w")] + WINDOW +
             ["--units", "us,kPa"] + extra, 0, png(s + "_w")),
            (s, "PREFIX.h5 for PREFIX, µs and MPa as two options",
             [h5, "-o", png(s + "_m"), "--units", "µs", "--units", "MPa"], 0,
             png(s + "_m")),
            (s, "a missing output", [os.path.join(work, "nothing_here"), "-o", png(s + "_x")],
             2, missing),
        ]
    # the other failures, each by one script (they share _common's code)
    jobs += [
        ("blows", "seconds, the window in seconds", [struck, "-o", png("blows_s"), "--units",
                                                     "s", "--t-max", "0.0005"], 0,
         png("blows_s")),
        ("xt", "a damaged PREFIX.h5", [os.path.join(work, "damaged"), "-o", png("xt_d")], 2,
         ["cannot read the run", "damaged"]),
        ("profiles", "a text run without .evt", [os.path.join(work, "no_evt"), "-o",
                                                 png("profiles_e")], 2,
         ["cannot read the run", "no_evt.evt"]),
        ("reaction", "a PNG that cannot be written", [ex2, "-o", os.path.join(work, "no",
                                                                               "x.png")], 2,
         ["cannot write", "x.png"]),
        ("fragments", "a unit that is none", [ex2, "-o", png("fragments_u"), "--units",
                                              "furlong"], 2, ["furlong"]),
        ("blows", "a time that is none", [struck, "-o", png("blows_t"), "--t-min", "soon"], 2,
         ["soon"]),
        ("gauges", "a gauge beyond the run's", [ex2, "-o", png("g3"), "--gauges", "3"], 2,
         ["--gauges 3", "2 gauges"]),
    ]
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        results = list(pool.map(invoke, jobs))
    for (s, what, args, status, expect), r in zip(jobs, results):
        name = f"{s}.py, {what}"
        check(r.returncode == status, f"{name}: exit {r.returncode}, not {status}: "
              f"{r.stderr.strip()[-400:]}")
        check("Traceback" not in r.stderr, f"{name}: a traceback: {r.stderr[-400:]}")
        if status == 0:
            check(png_ok(expect), f"{name}: no PNG {expect}")
        else:
            lines = r.stderr.strip().splitlines()
            if "furlong" not in expect and "soon" not in expect:     # argparse adds its usage
                check(len(lines) == 1 and lines[0].startswith(f"{s}.py: error: "),
                      f"{name}: not one line '{s}.py: error: ...': {r.stderr!r}")
            check(all(w in r.stderr for w in expect), f"{name}: {expect} not in {r.stderr!r}")
        print(f"{name}: exit {r.returncode}" + (f": {r.stderr.strip().splitlines()[-1]}"
                                                 if r.returncode else ""))
    in_process(check, plots, ex2, struck, ens, spall_run)
    return check.finish()


if __name__ == "__main__":
    sys.exit(main())
