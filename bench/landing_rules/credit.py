"""Issue 17, the landing of an odd bar held by a fixed top on the base (doc/method.md, "A
landing credit"): on the lattice model of bench/held_gravity.py, 24 runs of 3000 steps
(N = 3 ... 15 cells, homogeneous and layered, the base at 20-90 % of the hanging sag) with
the present rules and with two changes together: (1) the bar lifts off only where the
bottom face's continuum step 2 f_n is more than d*/2 = g dt^2 / (2 Z_n C) away from the
base, and then moves by 2 f_n + d*/2 (the minimum of the free measure over the face step:
the lift-off removes exactly K = g^2 dt^3 / (8 C)); (2) a landing that would add gamma
(<= K) books 0 and keeps gamma as a credit of the held bar (the held measure minus gamma,
constant while held), which the next lift-off pays (K - gamma >= 0). Prints the number of
events and the least and largest booked change per kind, in units of K, and the largest
penetration. python3 bench/landing_rules/credit.py"""
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np
from held_gravity import measure, held_M, Bar, reading


def step(b, u, du, held_bot):
    """one step of the lumped-mass scheme with a fixed top (as explore.py)"""
    s = (b.Z / b.dt) * (u[:-1] - u[1:])
    f = np.zeros(b.N + 1)
    f[1:] += s; f[:-1] -= s
    du2 = du + b.dt * b.dt / b.m * f + b.dt * b.dt * b.g
    du2[0] = 0
    if held_bot:
        du2[-1] = 0
    return u + du2, du2


def free_m(b, u, du):
    return measure(b.Z, b.m, u, du, b.dt, b.g, False, True)


def held_m(b, u, du):
    return held_M(b, u, du, True)


def run(b, u, du, base, held, nsteps, new_rules):
    C = np.sum(1 / b.Z)
    dstar = b.g * b.dt ** 2 / (b.Z[-1] * C) if (b.N % 2 and new_rules) else 0.0
    ev, credit, pen = [], 0.0, 0.0
    for n in range(nsteps):
        if held:
            u, du = step(b, u, du, True)
            h, sdt = reading(b.Z, b.m, u, du, b.dt, False, False, at_n=True)
            fN = (h[-1] + sdt[-1]) / b.Z[-1]
            if 2 * fN + dstar / 2 < 0:
                m0 = held_m(b, u, du) - credit
                x = 2 * fN + dstar / 2
                u = u.copy(); du = du.copy(); u[-1] += x - du[-1]; du[-1] = x
                ev.append(('lift-off', m0 - free_m(b, u, du)))
                held, credit = False, 0.0
        else:
            u2, du2 = step(b, u, du, False)
            if u2[-1] > base:
                m0 = free_m(b, u2, du2)
                u3 = u2.copy(); du3 = du2.copy(); u3[-1] = u[-1]; du3[-1] = 0.0
                loss = m0 - held_m(b, u3, du3)
                if new_rules and loss < 0:
                    credit, loss = -loss, 0.0
                ev.append(('landing', loss))
                u, du, held = u3, du3, True
            else:
                u, du = u2, du2
        pen = max(pen, u[-1] - base)
    return ev, pen


def hanging(b):
    w = np.array([b.g * np.sum(b.m[k + 1:]) for k in range(b.N)])
    u = np.zeros(b.N + 1)
    for k in range(b.N):
        u[k + 1] = u[k] + w[k] * b.dt / b.Z[k]
    return u


if __name__ == "__main__":
    for new_rules in (False, True):
        rng = np.random.default_rng(3)
        tot = {}
        worst_pen = 0.0
        for trial in range(24):
            N = rng.choice([3, 5, 7, 9, 11, 15])
            Z = np.ones(N) if trial % 2 else rng.uniform(0.5, 2, N)
            b = Bar(Z, 0.3, 1.0)
            K = b.g ** 2 * b.dt ** 3 / (8 * np.sum(1 / Z))
            us = hanging(b)
            base = us[-1] * rng.uniform(0.2, 0.9)
            u = np.minimum(us * rng.uniform(0.0, 1.0), base)
            du = np.zeros(N + 1); du[1:] = rng.normal(size=N) * 1e-3 * us[-1]; du[-1] = 0
            ev, pen = run(b, u, du, base, bool(u[-1] >= base), 3000, new_rules)
            worst_pen = max(worst_pen, pen / b.dt)
            for kind, loss in ev:
                t = tot.setdefault(kind, [0, np.inf, -np.inf])
                t[0] += 1; t[1] = min(t[1], loss / K); t[2] = max(t[2], loss / K)
        print(("credit and lift-off at d*/2" if new_rules else "present rules") + ": " +
              "; ".join(f"{k} {v[0]} events, booked change {v[1]:+.3e} K ... {v[2]:+.3e} K"
                        for k, v in tot.items()) + f"; largest penetration {worst_pen:.1e} dt (dx units)")
