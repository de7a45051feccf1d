#!/usr/bin/env python3
"""NumPy reference of the compact scheme (2.3) spallbar runs for bench/run.py's intact bar:
half-node model of one material (E = 2e11 Pa, rho = 8000 kg/m^3, dt = 1e-6 s, so
dx = a dt = 5 mm), free ends, the power-law load p0 (1 - t/t_k) (p0 = 1e8 Pa,
t_k = t_cut = 1e-4 s) on the top face in its stepwise form, no gravity. Written as a
competent NumPy user would: Python floats for the scalars, every array allocated once,
in-place ufuncs, one Python iteration per time step.

    P^n      = (1/(2 dt)) integral of p over [t^{n-1}, t^{n+1}]     (doc/method.md, loads)
    du^{n+1} = du^n + (s_i - s_{i+1}) dt^2 / m_i   (s_0 = P^n, s_{N+1} = 0: the faces)
    u^{n+1}  = u^n + du^{n+1}
    s^{n+1}  = s^n + (E/dx) (du_{k-1} - du_k)                       (cells k = 1..N)

usage: numpy_ref.py CELLS STEPS [--out FILE.npz] [--variant lean|old]
  prints the wall time of the time loop and node-steps/s; --out saves the final state
  (x, u, v = du/dt, s of the cells) for bench/check_refs.py.
  --variant old: the reference bench/run.py used up to issue 21 (kept only to time it):
  its stiffness and masses were NumPy float64 scalars (a from np.sqrt), every step
  allocated its temporaries, and its load was the mean over [t^n, t^{n+1}], not the
  stepwise form, so it did not compute spallbar's numbers either.
"""
import argparse
import math
import time

import numpy as np

YOUNG, RHO, DT = 2.0e11, 8000.0, 1.0e-6        # [Pa], [kg/m^3], [s]
P0, T_K, T_CUT = 1.0e8, 1.0e-4, 1.0e-4          # [Pa], [s], [s]: p = p0 (1 - t/t_k), t < t_cut


def stepwise_load(n, dt=DT):
    """P^n: the mean of p0 (1 - t/t_k) over [t^{n-1}, t^{n+1}] (p = 0 outside [0, t_cut])."""
    lo = max((n - 1) * dt, 0.0)
    hi = min((n + 1) * dt, T_CUT)
    if not hi > lo:
        return 0.0
    return P0 * (hi - lo) * (1.0 - (hi + lo) / (2.0 * T_K)) / (2.0 * dt)


def run(cells, steps, young=YOUNG, rho=RHO, dt=DT):
    """The lean loop. Returns u, du of nodes 0..N and s of cells 1..N after `steps` steps."""
    a = math.sqrt(young / rho)                   # Python floats throughout
    dx = a * dt
    dm = rho * dx
    stiff = young / dx
    c = np.full(cells + 1, dt * dt / dm)         # dt^2 / m_i
    c[0] = c[-1] = dt * dt / (0.5 * dm)          # half masses at the free ends
    load = [stepwise_load(n, dt) for n in range(steps)]
    s = np.zeros(cells + 2)                      # s[0], s[N+1]: the face stresses
    du = np.zeros(cells + 1)
    u = np.zeros(cells + 1)
    f = np.empty(cells + 1)                      # work arrays, allocated once
    g = np.empty(cells)
    s_above, s_below, s_cells = s[:-1], s[1:], s[1:-1]
    du_above, du_below = du[:-1], du[1:]
    for n in range(steps):
        s[0] = load[n]
        np.subtract(s_above, s_below, out=f)
        np.multiply(f, c, out=f)
        np.add(du, f, out=du)
        np.add(u, du, out=u)
        np.subtract(du_above, du_below, out=g)
        np.multiply(g, stiff, out=g)
        np.add(s_cells, g, out=s_cells)
    return u, du, s[1:-1].copy()


def run_old(cells, steps, young=YOUNG, rho=RHO, dt=DT, p0=P0, t_k=T_K):
    """The superseded reference, verbatim (see the module docstring): timing only."""
    a = np.sqrt(young / rho)
    dx = a * dt
    dm = rho * dx
    m = np.full(cells + 1, dm)
    m[0] = m[-1] = 0.5 * dm
    c = dt * dt / m
    stiff = young / dx
    s = np.zeros(cells + 2)
    du = np.zeros(cells + 1)
    u = np.zeros(cells + 1)
    for n in range(steps):
        t0, t1 = n * dt, (n + 1) * dt
        if t0 < t_k:
            t1 = min(t1, t_k)
            s[0] = p0 * ((t1 - t0) - (t1 * t1 - t0 * t0) / (2.0 * t_k)) / dt
        else:
            s[0] = 0.0
        du += (s[:-1] - s[1:]) * c
        u += du
        s[1:-1] += stiff * (du[:-1] - du[1:])
    return u, du, s[1:-1].copy()


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cells", type=int)
    p.add_argument("steps", type=int)
    p.add_argument("--out", help="save the final state here (.npz)")
    p.add_argument("--variant", choices=("lean", "old"), default="lean")
    args = p.parse_args()
    fn = run if args.variant == "lean" else run_old
    t = time.perf_counter()
    u, du, s = fn(args.cells, args.steps)
    wall = time.perf_counter() - t
    print(f"numpy ({args.variant}): {args.cells} cells, {args.steps} steps, loop {wall:.3f} s, "
          f"{(args.cells + 1) * args.steps / wall:.3e} node-steps/s")
    if args.out:
        dx = math.sqrt(YOUNG / RHO) * DT
        np.savez(args.out, x=np.arange(args.cells + 1) * dx, u=u, v=du / DT, s=s)


if __name__ == "__main__":
    main()
