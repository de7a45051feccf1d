"""Issue 17 (doc/method.md, "A landing credit"): a fragment held at its bottom (the base)
with a free top face, under gravity, on the lattice model of bench/held_gravity.py: the
measure as a function of the top face's step over the last step is a parabola whose minimum
lies g dt^2 / (2 Z_1 C) beyond the g = 0 one and K_frag = g^2 dt^3 / (8 C) lower, whatever
the state, for an odd cell count; for an even one the two minima coincide. Prints the offset
and the depth (in units of K_frag) for three random states per fragment.
python3 bench/landing_rules/face_parabola.py"""
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
import numpy as np
from held_gravity import measure, Bar


def vertex(b, m, u, du):
    """step of the top face at the measure's minimum, and the measure there"""
    def M(x):
        u2 = u.copy(); du2 = du.copy(); u2[0] += x - du[0]; du2[0] = x
        return measure(b.Z, m, u2, du2, b.dt, b.g, True, False)
    x0 = du[0]
    l0, l1, l2 = M(x0 - 1), M(x0), M(x0 + 1)
    a, bb = (l0 + l2 - 2 * l1) / 2, (l2 - l0) / 2
    xs = x0 - bb / (2 * a)
    return xs, M


if __name__ == "__main__":
    rng = np.random.default_rng(5)
    for N in range(1, 8):
        for hom in (True, False):
            Z = np.ones(N) if hom else rng.uniform(0.5, 2, N)
            b, b0 = Bar(Z, 0.3, 1.0), Bar(Z, 0.3, 0.0)
            C = np.sum(1 / Z); K = b.g ** 2 * b.dt ** 3 / (8 * C)
            m = b.m.copy(); m[0] = b.mb[0]
            cols = []
            for _ in range(3):
                u = rng.normal(size=N + 1); du = rng.normal(size=N + 1); du[-1] = 0
                xs, M = vertex(b, m, u, du)
                xs0, _ = vertex(b0, m, u, du)
                cols.append(f"offset {(xs - xs0) / (b.g * b.dt ** 2 / (2 * Z[0] * C)):.6f} x g dt^2/(2 Z_1 C), "
                            f"depth {(M(xs0) - M(xs)) / K:.6f} K")
            print(f"N = {N} {'homogeneous' if hom else 'layered'}: " + "; ".join(cols))
