"""Issue 17, gravity on a bar held by a fixed top: a lattice model (port of spb_wave's reading
without loads) of lift-off, landing and the admissible break of a bar held at both ends (fixed
top; the base), with the numbers doc/method.md quotes (run it: python3 bench/held_gravity.py)."""
import numpy as np

def reading(Z, m, u, du, dt, eq_top, eq_bot, at_n=False):
    """Z: cells (n), m, u, du: the fragment's nodes (n+1, owned masses). Returns h, sdt."""
    n = len(Z)
    r = m * du / dt
    un = u - du
    sdt = (Z / dt) * ((un if at_n else u)[:-1] - (un if at_n else u)[1:]) * dt
    o = 0 if at_n else 1
    def s(k):  # sdt of cell k (1-based), k in 1..n
        return sdt[k - 1]
    hd = np.zeros(n)
    if eq_top:
        hd[0] = r[0] if at_n else r[0] - s(1)
    for k in range(1, n):       # h_dn(k+1) = r(k) - sdt(k+o) - h_dn(k)
        hd[k] = r[k] - s(k + o) - hd[k - 1]
    if eq_bot:
        hu = np.zeros(n)
        hu[n - 1] = r[n] - s(n) if at_n else r[n]
        for k in range(n - 1, 0, -1):
            hu[k - 1] = r[k] - s(k + o) - hu[k]
    if eq_top and eq_bot:
        h = 0.5 * (hd + hu)
    elif eq_top:
        h = hd
    elif eq_bot:
        h = hu
    else:
        sg = (-1.0) ** np.arange(n)
        alpha = -np.sum(sg * (2 * hd + sdt) / Z) / np.sum(2 / Z)
        h = hd + sg * alpha
    return h, sdt

def measure(Z, m, u, du, dt, g, eq_top, eq_bot, whole_held=False, base_u=None, base_fix=0):
    n = len(Z)
    h, sdt = reading(Z, m, u, du, dt, eq_top, eq_bot)
    e = np.sum((h**2 + (h + sdt)**2) / Z) / dt
    r = m * du / dt
    jp = r[0] + sum((-1) ** i * (r[i] + sdt[i - 1]) for i in range(1, n + 1))
    if eq_top and not eq_bot and n % 2 == 1:
        jp = -jp
    extra = 0.0
    if not eq_top and not eq_bot and n % 2 == 1 and whole_held:
        C = np.sum(1 / Z); Ca = np.concatenate([[0], np.cumsum(1 / Z)])
        w = (-1.0) ** (np.arange(n + 1) - 1) * (0.5 - Ca / C)
        jp = 4 / dt * np.sum(w * m * (u - 0.5 * du))
        if base_fix:
            extra = -0.5 * g * dt / C * (u[-1] - 0.5 * du[-1] + 0.25 * g * dt**2)
    epot = -g * np.sum(m * (u - 0.5 * du))
    return e + epot - 0.5 * g * dt * jp + extra

class Bar:
    def __init__(s, Z, dt, g):
        s.Z = np.asarray(Z, float); s.N = len(Z); s.dt = dt; s.g = g
        s.ma = np.concatenate([[0.0], s.Z * dt / 2])   # upper halves
        s.mb = np.concatenate([s.Z * dt / 2, [0.0]])   # lower halves
        s.m = s.ma + s.mb

def both_held_M(b, u, du, base, base_fix):
    return measure(b.Z, b.m, u, du, b.dt, b.g, False, False, True, base_fix=base_fix and base)

def fracture(b, u, du, i, base, base_fix, da=0.0, db=0.0):
    """Break node i of the whole held bar (state u, du at t^{n+1}); return booked change."""
    N, dt = b.N, b.dt
    M0 = both_held_M(b, u, du, base, base_fix)
    h, sdt = reading(b.Z, b.m, u, du, dt, False, False, at_n=True)
    f = (h + sdt) / b.Z; gg = h / b.Z
    duA = 2 * f[i - 1] + da; duB = 2 * gg[i] + db       # cell i above, cell i+1 below
    un = u - du
    # upper fragment 0..i (node i: upper half), lower i..N (node i: lower half)
    uU = u[:i + 1].copy(); duU = du[:i + 1].copy(); uU[-1] = un[i] + duA; duU[-1] = duA
    mU = b.m[:i + 1].copy(); mU[-1] = b.ma[i]
    uL = u[i:].copy(); duL = du[i:].copy(); uL[0] = un[i] + duB; duL[0] = duB
    mL = b.m[i:].copy(); mL[0] = b.mb[i]
    M1 = measure(b.Z[:i], mU, uU, duU, dt, b.g, False, True) + \
         measure(b.Z[i:], mL, uL, duL, dt, b.g, True, False)
    return M0 - M1


def held_M(b, u, du, uN_term):
    """The measure of the whole bar held at both ends; uN_term: with (u_n - du_n/2)/C."""
    M = measure(b.Z, b.m, u, du, b.dt, b.g, False, False, True)
    if uN_term and b.N % 2 == 1:
        M -= 0.5 * b.g * b.dt * (u[-1] - 0.5 * du[-1]) / np.sum(1 / b.Z)
    return M


def lift_off(b, u, du, uN_term):
    """Booked change of an admissible lift-off (the bottom face moves by 2 f_n over the step)."""
    h, sdt = reading(b.Z, b.m, u, du, b.dt, False, False, at_n=True)
    fN = (h[-1] + sdt[-1]) / b.Z[-1]
    u2, du2 = u.copy(), du.copy()
    u2[-1] += 2 * fN - du[-1]; du2[-1] = 2 * fN
    return held_M(b, u, du, uN_term) - measure(b.Z, b.m, u2, du2, b.dt, b.g, False, True)


def landing(b, u, du, uN_term):
    """Booked change of a landing at t^n of a free-bottom state, and d (the face's trial step
    beyond the lift-off's from the landed state)."""
    u2, du2 = u.copy(), du.copy()
    u2[-1] -= du[-1]; du2[-1] = 0.0
    h, sdt = reading(b.Z, b.m, u2, du2, b.dt, False, False, at_n=True)
    d = du[-1] - 2 * (h[-1] + sdt[-1]) / b.Z[-1]
    return measure(b.Z, b.m, u, du, b.dt, b.g, False, True) - held_M(b, u2, du2, uN_term), d


if __name__ == "__main__":
    # python3 bench/held_gravity.py: the lattice model's numbers quoted in doc/method.md
    rng = np.random.default_rng(0)
    for N in (3, 4, 5, 7):
        Z = rng.uniform(0.5, 2, N); dt = 0.3; g = 1.0
        b, b0 = Bar(Z, dt, g), Bar(Z, dt, 0.0)
        C = np.sum(1 / Z); c = Z[-1] ** 2 * C / (2 * dt); K = g * g * dt ** 3 / (8 * C)
        worst = {"lift old": 0, "lift new": 0, "break": 0, "landing - (c d^2 - g m d)": 0}
        for t in range(200):
            u = rng.normal(size=N + 1); du = rng.normal(size=N + 1); u[0] = du[0] = 0; du[-1] = 0
            for key, fix in (("lift old", False), ("lift new", True)):
                worst[key] = max(worst[key], abs(lift_off(b, u, du, fix) - lift_off(b0, u, du, fix)))
            for i in range(1, N):
                # fracture() books with the measure without the u_n term; add it back
                Dn = fracture(b, u, du, i, True, 0) + (held_M(b, u, du, True) - held_M(b, u, du, False)) \
                    - fracture(b0, u, du, i, True, 0)
                worst["break"] = max(worst["break"], abs(Dn))
            uf = rng.normal(size=N + 1); duf = rng.normal(size=N + 1); uf[0] = duf[0] = 0
            dl, d = landing(b, uf, duf, True)
            dl0, _ = landing(b0, uf, duf, True)
            lin = -g * b.m[-1] * d if N % 2 == 1 else 0.0
            worst["landing - (c d^2 - g m d)"] = max(worst["landing - (c d^2 - g m d)"],
                                                     abs(dl - c * d * d - lin), abs(dl0 - c * d * d))
        print(f"N = {N}: " + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()) +
              f"; landing's least change -K = {-K if N % 2 else 0.0:.3e}")
