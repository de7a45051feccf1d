#!/usr/bin/env python3
"""The intact-bar benchmark case and its two references, and the check that keeps them honest.

The case (INTACT, intact_deck): one material (E = 2e11 Pa, rho = 8000 kg/m^3), dt = 1e-6 s,
so dx = a dt = 5 mm and a bar of CELLS x 5 mm; free ends; p0 (1 - t/t_k) on the top face.
The references compute the same scheme outside spallbar:

  bench/numpy_ref.py   a lean NumPy loop (Python float scalars, in-place ufuncs)
  bench/naive_ref.f90  a naive Fortran loop (two loops per step), compiled by build_naive
                       with spallbar's Release flags (release_flags)

check() runs spallbar on the deck with a profile at t_end in PREFIX.h5 (full precision),
runs both references with their final state saved, and compares u, v and the cell stresses
of every node: max |ref - spallbar| / max |spallbar| per field must stay below TOLERANCE.

usage (ctest bench.references; results only, nothing is timed):
  references.py --exe SPALLBAR --work DIR [--cells 1000] [--steps 200] [--fc gfortran]
                [--fflags "..."]
"""
import argparse
import os
import re
import shlex
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# The references agree with spallbar to round-off, not to the bit: NumPy multiplies by a
# precomputed dt^2/m where spallbar multiplies by 1/m, then by dt^2, and spallbar integrates
# the load through expm1/log1p. Each step adds O(1e-16) relative differences; the free-free
# bar's zig-zag mode (doc/method.md, "The zig-zag Jordan block at dx = a dt") lets them grow
# linearly, so after 2000 steps a few 1e-14
# at most. 1e-12 leaves two decades of margin and still catches any change of the scheme
# (a load window off by half a step, as in the old NumPy reference, is a 1e-2 difference).
TOLERANCE = 1.0e-12

INTACT = """&run
  title = 'intact bar benchmark, {cells} cells'
  t_end = {t_end}
  history_every = 1000000000
{extra}/
&mesh
  dt = 1.0e-6
/
&segments
  n = 1
  length = {length}
  young = 2.0e11
  density = 8000.0
/
&ends
  top = 'free'
  bottom = 'free'
/
&load kind = 'power', p0 = 1.0e8, t_k = 1.0e-4, exponent = 1.0, t_cut = 1.0e-4 /
"""


def intact_deck(work, cells, steps, profile=False):
    """Write the intact-bar deck for CELLS cells and STEPS steps into WORK; with profile, a
    profile at t_end into PREFIX.h5 (&run profile_times, hdf5)."""
    t_end = f"{steps * 1.0e-6:.10g}"
    extra = f"  profile_times = {t_end}\n  hdf5 = .true.\n" if profile else ""
    path = os.path.join(work, f"intact_{cells}_{steps}{'_profile' if profile else ''}.nml")
    with open(path, "w") as f:
        f.write(INTACT.format(cells=cells, t_end=t_end, length=f"{cells * 5.0e-3:.10g}",
                              extra=extra))
    return path


def release_flags(exe=None):
    """spallbar's Release Fortran flags: SPALLBAR_RELEASE_FLAGS of CMakeLists.txt, with
    -march=native when the build folder of EXE (bin/.. of it) has SPALLBAR_NATIVE on (the
    default)."""
    text = open(os.path.join(ROOT, "CMakeLists.txt")).read()
    m = re.search(r"set\(SPALLBAR_RELEASE_FLAGS\s+([^)]*)\)", text)
    if not m:
        raise RuntimeError("CMakeLists.txt: no set(SPALLBAR_RELEASE_FLAGS ...)")
    flags = m.group(1).split()
    native = True
    if exe:
        cache = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(exe))),
                             "CMakeCache.txt")
        if os.path.exists(cache):
            native = re.search(r"^SPALLBAR_NATIVE:BOOL=(ON|TRUE|1)\s*$", open(cache).read(),
                               re.M | re.I) is not None
    if native:
        flags.append("-march=native")
    return flags


def build_naive(work, fc="gfortran", flags=None):
    """Compile bench/naive_ref.f90 in WORK; returns the executable and the command used."""
    exe = os.path.join(work, "naive_ref")
    cmd = [fc] + list(flags if flags is not None else release_flags()) + \
        [os.path.join(HERE, "naive_ref.f90"), "-o", exe]
    subprocess.run(cmd, cwd=work, check=True)
    return exe, " ".join(shlex.quote(c) for c in cmd)


def read_naive(path):
    """The final state naive_ref wrote: u, v of nodes 0..N, s of cells 1..N."""
    raw = open(path, "rb").read()
    n = int(np.frombuffer(raw[:8], dtype=np.int64)[0])
    vals = np.frombuffer(raw[8:], dtype=np.float64)
    if vals.size != 3 * n + 2:
        raise RuntimeError(f"{path}: {vals.size} reals for N = {n}, expected {3 * n + 2}")
    return vals[:n + 1], vals[n + 1:2 * n + 2], vals[2 * n + 2:]


def read_spallbar(h5path):
    """u, v, stress of every half-node row of the last profile in PREFIX.h5."""
    import h5py
    with h5py.File(h5path, "r") as f:
        grp = f["/fields/profiles"]
        last = grp[sorted(grp.keys())[-1]]
        return last["u"][()], last["v"][()], last["stress"][()], int(last.attrs["step"])


def half_rows(u, v, s):
    """Node values (0..N) and cell stresses (1..N) as spallbar's half-node rows: B_0, A_1,
    B_1, ..., A_N; a half takes its node's u and v and the stress of its cell."""
    return np.repeat(u, 2)[1:-1], np.repeat(v, 2)[1:-1], np.repeat(s, 2)


def rel_diff(ref, spb):
    """max |ref - spb| / max |spb| over the rows (the field's own scale)."""
    scale = np.max(np.abs(spb))
    return float(np.max(np.abs(ref - spb)) / scale) if scale > 0 else float(np.max(np.abs(ref)))


def check(exe, work, cells, steps, naive_exe, python=sys.executable):
    """Run spallbar and both references on the intact bar; returns {reference: {field:
    relative difference}} (see rel_diff)."""
    deck = intact_deck(work, cells, steps, profile=True)
    prefix = os.path.join(work, f"check_{cells}")
    subprocess.run([exe, deck, "-q", "--output", prefix], cwd=work, check=True,
                   stdout=subprocess.DEVNULL)
    su, sv, ss, step = read_spallbar(prefix + ".h5")
    if step != steps or su.size != 2 * cells:
        raise RuntimeError(f"spallbar profile at step {step} with {su.size} rows, expected "
                           f"step {steps} and {2 * cells} rows")
    npz = os.path.join(work, f"numpy_{cells}.npz")
    subprocess.run([python, os.path.join(HERE, "numpy_ref.py"), str(cells), str(steps),
                    "--out", npz], cwd=work, check=True, stdout=subprocess.DEVNULL)
    d = np.load(npz)
    states = {"numpy": (d["u"], d["v"], d["s"])}
    out = os.path.join(work, f"naive_{cells}.bin")
    subprocess.run([naive_exe, str(cells), str(steps), out], cwd=work, check=True,
                   stdout=subprocess.DEVNULL)
    states["naive"] = read_naive(out)
    result = {}
    for name, (u, v, s) in states.items():
        ru, rv, rs = half_rows(u, v, s)
        result[name] = {"u": rel_diff(ru, su), "v": rel_diff(rv, sv), "stress": rel_diff(rs, ss)}
    return result


def worst(result):
    return max(x for fields in result.values() for x in fields.values())


def describe(result):
    return "; ".join(f"{name}: " + ", ".join(f"{k} {x:.1e}" for k, x in fields.items())
                     for name, fields in result.items())


def main():
    p = argparse.ArgumentParser(description="the references against spallbar (no timing)")
    p.add_argument("--exe", required=True, help="spallbar")
    p.add_argument("--work", required=True, help="folder for the runs (made if missing)")
    p.add_argument("--cells", type=int, default=1000)
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--fc", default="gfortran")
    p.add_argument("--fflags", help="flags for naive_ref.f90 (default: spallbar's Release "
                                    "flags)")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    flags = shlex.split(args.fflags) if args.fflags is not None else release_flags()
    naive, cmd = build_naive(args.work, args.fc, flags)
    print(cmd)
    result = check(os.path.abspath(args.exe), args.work, args.cells, args.steps, naive)
    w = worst(result)
    print(f"N = {args.cells}, {args.steps} steps, max |ref - spallbar| / max |spallbar|: "
          f"{describe(result)}; tolerance {TOLERANCE:.0e}")
    if not w <= TOLERANCE:
        print("FAIL: a reference does not compute what spallbar computes", file=sys.stderr)
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
