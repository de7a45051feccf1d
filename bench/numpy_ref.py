#!/usr/bin/env python3
"""NumPy reference of the same compact scheme (2.3) spallbar runs for an intact bar:
half-node model, one material, free ends, the stepwise power-law load on the top face,
no gravity. Vectorised over nodes; one Python step per time step.

    du^{n+1} = du^n + (s_i - s_{i+1}) dt^2 / m_i          (joined nodes)
    u^{n+1}  = u^n + du^{n+1}
    s^{n+1}  = s^n + (E/dx) (du_{i-1} - du_i)

usage: numpy_ref.py CELLS STEPS  -> prints node-steps/s and a checksum
"""
import sys
import time

import numpy as np


def run(cells, steps, young=2.0e11, rho=8000.0, dt=1.0e-6, p0=1.0e8, t_k=1.0e-4):
    a = np.sqrt(young / rho)
    dx = a * dt
    dm = rho * dx
    m = np.full(cells + 1, dm)
    m[0] = m[-1] = 0.5 * dm                       # half masses at the free ends
    c = dt * dt / m
    stiff = young / dx
    s = np.zeros(cells + 2)                        # s[0], s[n+1]: end stresses
    du = np.zeros(cells + 1)
    u = np.zeros(cells + 1)
    for n in range(steps):
        t0, t1 = n * dt, (n + 1) * dt             # the stepwise (window-mean) load
        if t0 < t_k:
            t1 = min(t1, t_k)
            s[0] = p0 * ((t1 - t0) - (t1 * t1 - t0 * t0) / (2.0 * t_k)) / dt
        else:
            s[0] = 0.0
        du += (s[:-1] - s[1:]) * c
        u += du
        s[1:-1] += stiff * (du[:-1] - du[1:])
    return u, s


def main():
    cells, steps = int(sys.argv[1]), int(sys.argv[2])
    t = time.perf_counter()
    u, s = run(cells, steps)
    wall = time.perf_counter() - t
    print(f"numpy: {cells} cells, {steps} steps, {wall:.3f} s, "
          f"{(cells + 1) * steps / wall:.3e} node-steps/s, checksum {np.sum(u):.6e}")


if __name__ == "__main__":
    main()
