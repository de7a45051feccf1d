#!/usr/bin/env python3
"""Ensembles (issue 34, doc/sweeps.md "Ensembles"): `&sweep perturb` and `ensemble_columns`.

1. Closed form: an elastic bar (no fracture, no gravity, unstressed start) under a constant
   pressure p0 on its top and fixed at its bottom is linear in p0, so every history column
   of realization i is (v_i / p0) times the unperturbed run's. From the perturbed values
   v_i of PREFIX_sweep.h5 (/cases/value) and one ordinary run the test computes the mean,
   population std, min and max at every history time and the predictability horizon by the
   documented rule, and compares PREFIX.ens (1e-12 of the column's scale) and its header.
   spread = 0: std exactly 0, horizon not reached.
2. PREFIX.ens, its HDF5 twin /ensemble and the summary's horizon lines byte-identical on 1,
   2 and 3 MPI ranks, static and dynamic, and without mpirun (Example 3 case 2 at h/19,
   which the perturbation makes chaotic: a horizon is reached).
3. An ensemble of Weibull strength fields (no perturb); an ordinary sweep writes no .ens.
4. Bad input: exit 2, one line naming &sweep and the variable, no file written.

usage: cli_ensemble.py SPALLBAR INPUT_DIR WORK_DIR MPIEXEC|-
"""
import math
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

from clitools import Checks, history, run

exe, indir, work, mpiexec = sys.argv[1:5]
check = Checks()
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

P0 = 1.0e5
LINEAR = """&run title = 'linear ensemble', t_end = 0.05 /
&mesh cells = 19 /
&segments n = 1, length = 0.95, young = 20.0e6, density = 1765.8, strength = -1.0 /
&ends top = 'free', bottom = 'fixed' /
&load kind = 'power',
  p0 = 1.0e5 /
"""
COLUMNS = ["reaction_bottom", "i_ends", "momentum"]
SWEEP = """&sweep
  perturb = 'p0'
  spread = {spread}
  realizations = 16
  seed = 2026
  ensemble_columns = 'reaction_bottom', 'i_ends', 'momentum'
  horizon_tol = {tol}
/
"""


def sweep(tag, text, ranks=0, args=()):
    """Run text as WORK/tag.nml with --sweep (ranks 0: without mpirun); the process."""
    deck = os.path.join(work, tag + ".nml")
    with open(deck, "w") as f:
        f.write(text)
    cmd = [exe, "--sweep", deck, "-o", os.path.join(work, tag), *args]
    if ranks:
        cmd = [mpiexec, "--oversubscribe", "-np", str(ranks)] + cmd
    p = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=900,
                       stdin=subprocess.DEVNULL)
    check(p.returncode == 0, f"{tag}: exit {p.returncode}: {p.stderr.strip()[:400]}")
    other = [l for l in p.stderr.splitlines() if not l.startswith("spallbar sweep: ")]
    check(other == [], f"{tag}: nothing on stderr but the progress: {other[:6]}")
    return p


def ens_table(tag):
    """PREFIX.ens: its columns by name (numpy arrays) and its '#' lines."""
    path = os.path.join(work, tag + ".ens")
    head = [l.rstrip("\n") for l in open(path) if l.startswith("#")]
    cols = history(path)
    return {k: np.array(v) for k, v in cols.items()}, head


def horizons(lines):
    """'horizon C: ...' lines (header or summary) as {C: seconds, or None not reached}."""
    out = {}
    for line in lines:
        m = re.match(r"^[# ]*horizon (\w+): (.*)$", line)
        if m:
            rest = m.group(2)
            out[m.group(1)] = None if rest.startswith("not reached") else float(rest.split()[0])
    return out


def stats(x):
    """Mean, population std, min, max over axis 0, as PREFIX.ens documents them."""
    lo, hi = x.min(axis=0), x.max(axis=0)
    mean = x.mean(axis=0)
    std = np.sqrt(((x - mean) ** 2).mean(axis=0))
    same = lo == hi
    return np.where(same, lo, mean), np.where(same, 0.0, std), lo, hi


def expected_horizon(t, series, tol):
    """The documented rule: whole 1 ms windows before t_end, window of a row floor(t/1 ms);
    the first window whose std over realizations of the window means exceeds tol x the
    largest |mean window mean|; (horizon or None, the margin of the decision)."""
    nwin = int(t[-1] / 1e-3 + 1e-9)
    w = (t / 1e-3).astype(int)
    means = np.array([[s[w == k].mean() for k in range(nwin) if (w == k).any()]
                      for s in series])
    ks = [k for k in range(nwin) if (w == k).any()]
    m, sd, _, _ = stats(means)
    scale = np.abs(m).max()
    margin = np.abs(sd - tol * scale).min() / max(tol * scale, 1e-300)
    for j, k in enumerate(ks):
        if sd[j] > tol * scale:
            return k / 1000.0, margin
    return None, margin


# -- 1. closed form
base_deck = os.path.join(work, "linear_base.nml")
with open(base_deck, "w") as f:
    f.write(LINEAR)
p = run(exe, ["linear_base.nml", "-q"], work)
check(p.returncode == 0, f"the unperturbed run: exit {p.returncode} {p.stderr}")
base = {k: np.array(v) for k, v in history(os.path.join(work, "linear_base.his")).items()}

p = sweep("linear", LINEAR + SWEEP.format(spread="1.0e-3", tol="0.01"))
with h5py.File(os.path.join(work, "linear_sweep.h5")) as h:
    values = h["cases/value"][()]
    h_t = h["ensemble/t"][()]
    h_mean = h["ensemble/reaction_bottom_mean"][()]
check(len(values) == 16 and len(set(values)) == 16, f"16 distinct perturbed values: {values}")
check(np.all(np.abs(values / P0 - 1) < 1e-3) and np.any(values > P0) and np.any(values < P0),
      f"values within p0 (1 +- 1e-3), on both sides: {values / P0 - 1}")
text_values = [float(l.split()[5]) for l in open(os.path.join(work, "linear.sweep"))
               if l.startswith(" ")]
check(np.allclose(text_values, values, rtol=1e-12, atol=0), "PREFIX.sweep's value column = h5")
ens, head = ens_table("linear")
check(np.array_equal(ens["t"], base["t"]), "PREFIX.ens rows at the history times of a run")
check(np.allclose(h_t, ens["t"], rtol=1e-12, atol=0) and
      np.allclose(h_mean, ens["reaction_bottom_mean"], rtol=1e-12, atol=0),
      "/ensemble holds the table (13 digits)")
worst = 0.0
for c in COLUMNS:
    series = np.outer(values / P0, base[c])
    scale = np.abs(series).max()
    for name, want in zip(("mean", "std", "min", "max"), stats(series)):
        err = np.abs(ens[f"{c}_{name}"] - want).max() / scale
        worst = max(worst, err)
        check(err < 1e-12, f"{c}_{name}: {err:.2e} of the column's scale (closed form)")
print(f"closed form: worst deviation {worst:.2e} of a column's scale "
      f"({len(ens['t'])} rows, 16 realizations)")
got = horizons(head)
for c in COLUMNS:
    want, margin = expected_horizon(base["t"], np.outer(values / P0, base[c]), 0.01)
    check(want is None and got.get(c, "missing") is None,
          f"{c}: horizon_tol 0.01 not reached (want {want}, header {got.get(c, 'missing')})")
# a horizon_tol that the impulse's growing spread passes half-way: its window (computed)
rel = values.std() / values.mean()
tol = float(f"{0.5 * rel:.3g}")
p = sweep("linear_tol", LINEAR + SWEEP.format(spread="1.0e-3", tol=repr(tol)))
ens2, head2 = ens_table("linear_tol")
got = horizons(head2)
summary = horizons(p.stdout.splitlines())
check(got == summary, f"the summary's horizons = the header's: {summary} {got}")
for c in ("i_ends", "reaction_bottom"):
    want, margin = expected_horizon(base["t"], np.outer(values / P0, base[c]), tol)
    print(f"{c}: horizon_tol {tol}: expected {want}, header {got.get(c)} (margin {margin:.1e})")
    if margin > 1e-9:
        check(got.get(c, "missing") == want, f"{c}: horizon {got.get(c)} = {want} (closed form)")
check(got.get("i_ends") is not None and 0.01 < got["i_ends"] < 0.049,
      f"the impulse's horizon lies inside the run: {got.get('i_ends')}")
# spread = 0: every realization is the run; std exactly 0, horizon not reached
p = sweep("spread0", LINEAR + SWEEP.format(spread="0.0", tol="1e-6"))
ens0, head0 = ens_table("spread0")
check(all(np.all(ens0[f"{c}_std"] == 0.0) for c in COLUMNS), "spread 0: std exactly 0")
check(all(np.array_equal(ens0[f"{c}_mean"], base[c]) for c in COLUMNS),
      "spread 0: mean = the run's history, bit for bit")
check(all(v is None for v in horizons(head0).values()) and len(horizons(head0)) == 3,
      f"spread 0: no horizon: {horizons(head0)}")

# -- 2. the same ensemble on any number of ranks (case 2, h/19: chaotic, a horizon)
case2 = open(os.path.join(indir, "example3_case2", "accelerate_above_h19.nml")).read()
case2 = re.sub(r"\n\s*profile_times[^\n]*", "", case2)
CASE2_SWEEP = """&sweep
  perturb = 'p0'
  spread = 1.0e-3
  realizations = 12
  seed = 7
  ensemble_columns = 'reaction_bottom', 'e_lost_w', 'e_wave'
  {extra}
/
"""
runs = [("c2_serial", 0, "")]
if mpiexec != "-":
    runs += [("c2_np1", 1, ""), ("c2_np2", 2, ""), ("c2_np3", 3, ""),
             ("c2_np2_dynamic", 2, "distribution = 'dynamic'"),
             ("c2_np3_dynamic", 3, "distribution = 'dynamic'")]
else:
    print("no mpiexec: MPI runs skipped (serial build)")
ref_rows = ref_head = ref_h5 = None
for tag, ranks, extra in runs:
    p = sweep(tag, case2 + CASE2_SWEEP.format(extra=extra), ranks)
    path = os.path.join(work, tag + ".ens")
    lines = open(path).read().splitlines()
    rows = [l for l in lines if l.startswith(" ")]
    hz = [l for l in lines if l.startswith("# horizon ")]
    said = [l for l in p.stdout.splitlines() if l.startswith("  horizon ")]
    with h5py.File(os.path.join(work, tag + "_sweep.h5")) as h:
        h5 = {k: h["ensemble"][k][()] for k in h["ensemble"]}
    if ref_rows is None:
        ref_rows, ref_head, ref_said, ref_h5 = rows, hz, said, h5
        steps = int(open(os.path.join(work, tag + ".sweep")).read().splitlines()[-1].split()[17])
        check(len(rows) == steps + 1 and len(hz) == 3,
              f"{tag}: a row per step and t = 0 ({steps} steps), 3 horizons: {len(rows)}")
        check(any(v is not None for v in horizons(hz).values()),
              f"{tag}: the chaotic case reaches a horizon: {hz}")
        print(f"{tag}: " + "; ".join(s.strip() for s in said))
        if not extra:
            ref_file = open(path, "rb").read()
        continue
    check(rows == ref_rows, f"{tag}: PREFIX.ens rows = serial ones, byte for byte")
    check(hz == ref_head and said == ref_said, f"{tag}: the horizons = serial ones")
    check(set(h5) == set(ref_h5) and all(np.array_equal(h5[k], ref_h5[k], equal_nan=True)
                                         for k in h5), f"{tag}: /ensemble = serial one")
    if not extra:
        check(open(path, "rb").read() == ref_file.replace(b"c2_serial", tag.encode()),
              f"{tag}: PREFIX.ens = serial one, whole file")

# -- 3. an ensemble of strength fields; an ordinary sweep writes no PREFIX.ens
weibull = open(os.path.join(indir, "sweeps", "weibull_spall.nml")).read()
weibull = weibull.replace("values       = 1.6e8, 2.0e8, 3.0e8", "").replace(
    "vary         = 'p0'", "").replace("realizations = 32", "realizations = 4")
sweep("plain", weibull, args=["-q"])
check(not os.path.exists(os.path.join(work, "plain.ens")), "an ordinary sweep: no PREFIX.ens")
p = sweep("fields", weibull.replace("&sweep", "&sweep\n  ensemble_columns = 'fragments', "
                                              "'e_fracture', 'reaction_bottom'"))
ensw, headw = ens_table("fields")
check(len(ensw["t"]) == 1001 and "# ensemble: 4 of 4 realizations" in "\n".join(headw),
      f"fields: 1001 rows over 4 realizations ({len(ensw['t'])})")
check(ensw["fragments_max"][-1] > ensw["fragments_min"][-1],
      f"fields: the strength fields give different fragments at t_end")

# -- 4. bad input: exit 2, one line naming &sweep and the variable, nothing written
lin_sweep = LINEAR + SWEEP.format(spread="1.0e-3", tol="0.01")
bad = {  # deck text: the variable the message must name
    lin_sweep.replace("'p0'", "'nonsense'"): "perturb",
    lin_sweep.replace("'p0'", "'t_k'"): "perturb",
    lin_sweep.replace("'p0'", "'gravity'"): "perturb",
    lin_sweep.replace("'p0'", "'young(1)'"): "perturb",
    lin_sweep.replace("realizations = 16", "realizations = 16\n  vary = 't_end'\n  "
                      "values = 0.05, 0.06"): "vary",
    lin_sweep.replace("realizations = 16", "realizations = 0"): "perturb",
    lin_sweep.replace("spread = 1.0e-3", "spread = -0.1"): "spread",
    lin_sweep.replace("spread = 1.0e-3", "spread = 1.0"): "spread",
    lin_sweep.replace("horizon_tol = 0.01", "horizon_tol = 0.0"): "horizon_tol",
    lin_sweep.replace("horizon_tol = 0.01", "horizon_tol = -1.0"): "horizon_tol",
    lin_sweep.replace("'momentum'", "'nonsense'"): "ensemble_columns(3)",
    lin_sweep.replace("'momentum'", "'i_ends'"): "ensemble_columns(3)",
    lin_sweep.replace("perturb = 'p0'", "").replace("spread = 1.0e-3", "")
    .replace("realizations = 16", "vary = 'p0'\n  values = 1e5, 2e5"): "ensemble_columns",
    lin_sweep.replace("perturb = 'p0'", "vary = 'p0'\n  values = 1e5"): "spread",
    lin_sweep.replace("  ensemble_columns = 'reaction_bottom', 'i_ends', 'momentum'\n", ""):
        "horizon_tol",
    # a perturbation beyond the deck's limits: t_cut may not exceed t_k
    lin_sweep.replace("p0 = 1.0e5", "p0 = 1.0e5\n  exponent = 1.0\n  t_k = 0.02\n  t_cut = 0.02")
    .replace("'p0'", "'t_cut'"): "perturb",
    weibull.replace("realizations = 4", "realizations = 4\n  perturb = 'p0'"): "perturb",
}
for k, (text, var) in enumerate(bad.items()):
    name = f"bad{k}"
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(text)
    before = set(os.listdir(work))
    p = run(exe, ["--sweep", name + ".nml"], work)
    lines = p.stderr.strip().splitlines()
    check(p.returncode == 2, f"{name} ({var}): exit {p.returncode}: {p.stderr.strip()}")
    check(len(lines) == 1 and lines[0].startswith("spallbar: &sweep: ") and var in lines[0],
          f"{name}: one line naming &sweep and {var}: {lines}")
    check(set(os.listdir(work)) - before == set(), f"{name}: no file left")
    print(f"{name}: {lines[0] if lines else ''}")

# the ensemble's memory beyond the limit: refused before any case runs, naming history_every
with open(os.path.join(work, "big.nml"), "w") as f:
    f.write(lin_sweep.replace("realizations = 16", "realizations = 100000"))
before = set(os.listdir(work))
p = subprocess.run([exe, "--sweep", "big.nml"], cwd=work, capture_output=True, text=True,
                   env=dict(os.environ, SPALLBAR_MEMORY_LIMIT="100000000"), timeout=600,
                   stdin=subprocess.DEVNULL)
lines = p.stderr.strip().splitlines()
check(p.returncode == 2 and len(lines) == 1 and "ensemble_columns (3 at 108 history rows: "
      "&run history_every = 1) need about 320.4 MB" in lines[0],
      f"the ensemble's memory: exit {p.returncode}: {lines}")
check(set(os.listdir(work)) - before == set(), "the ensemble's memory: no file left")

sys.exit(check.finish())
