"""Issue 17, a transmitting end under gravity: a lattice model of the intact scheme and the
admissible break with free, fixed and transmitting ends, gravity and face loads, and a port of
spb_wave's reading, with the rules before (OLD) and after (NEW) the transmitting end's gravity
terms; it prints the numbers doc/method.md quotes (python3 bench/transmit_gravity.py).

The three terms (doc/method.md, "A transmitting end under gravity"):
  1. the end's equation: the reading's incoming interval there is w_in + g dt^2/4 (not w_in);
  2. e_wave_g for an odd cell count: J' + 2 (m du/dt - Z (w_in + g dt^2/4)) at the end when the
     other end is held (J' counted from it); (top term) + (bottom term) alone with two
     transmitting ends;
  3. the work through the end Z du (2 w - du)/dt counts w = w_in + rho, rho the fragment's
     zig-zag content (the reading's incoming interval minus the equation's), which a free face
     and a transmitting end allow; the intact step takes rho to -rho.
"""
import copy

import numpy as np

OLD = dict(delta=False, odd=False, rho=False)
NEW = dict(delta=True, odd=True, rho=True)


class Lattice:
    """Cells Z (n), one time step dt, gravity g; ends 'free', 'fixed' or 'transmit' (a
    transmitting end: static stress sst, continuation velocity vf, virtual half mass)."""

    def __init__(s, Z, dt, g, top, bot, sst=(0.0, 0.0), vf=(0.0, 0.0), rules=NEW):
        s.Z = np.asarray(Z, float); s.N = len(s.Z); s.dt = dt; s.g = g
        s.top, s.bot, s.sst, s.vf, s.rules = top, bot, sst, vf, rules
        s.ma = np.concatenate([[0.0], s.Z * dt / 2])
        s.mb = np.concatenate([s.Z * dt / 2, [0.0]])
        if top == "transmit":
            s.ma[0] = s.Z[0] * dt / 2
        if bot == "transmit":
            s.mb[-1] = s.Z[-1] * dt / 2
        s.joined = np.ones(s.N + 1, bool)
        s.q = (0.0, 0.0)

    def set_state(s, u, du):
        s.ua, s.ub, s.dua, s.dub = u.copy(), u.copy(), du.copy(), du.copy()
        s.s = s.Z / s.dt * (u[:-1] - u[1:])
        s.s_old = s.s - s.Z / s.dt * (du[:-1] - du[1:])

    def w_in(s):
        dt, q = s.dt, s.q
        return ((0.5 * s.sst[0] * dt + q[0]) / s.Z[0] + 0.5 * s.vf[0] * dt,
                -(0.5 * s.sst[1] * dt + q[1]) / s.Z[-1] + 0.5 * s.vf[1] * dt)

    def delta(s):
        return s.g * s.dt ** 2 / 4 if s.rules["delta"] else 0.0

    def step(s, q_prev, q):
        """the trial step with the stepwise loads P^n = (q_prev + q)/(2 dt)"""
        dt, Z = s.dt, s.Z
        P = (np.asarray(q_prev) + np.asarray(q)) / (2 * dt)
        st = {"free": P[0], "fixed": 0.0,
              "transmit": s.sst[0] - Z[0] / dt * (s.dub[0] - s.vf[0] * dt) + 2 * P[0]}[s.top]
        sb = {"free": P[1], "fixed": 0.0,
              "transmit": s.sst[1] + Z[-1] / dt * (s.dua[-1] - s.vf[1] * dt) + 2 * P[1]}[s.bot]
        sf = np.concatenate([[st], s.s, [sb]])
        fa, fb = sf[:-1] + s.ma * s.g, -sf[1:] + s.mb * s.g
        dua, dub = s.dua.copy(), s.dub.copy()
        for i in range(s.N + 1):
            if s.joined[i]:
                dua[i] += (fa[i] + fb[i]) / (s.ma[i] + s.mb[i]) * dt * dt
                dub[i] = dua[i]
            else:
                dua[i] += fa[i] / s.ma[i] * dt * dt if s.ma[i] > 0 else 0.0
                dub[i] += fb[i] / s.mb[i] * dt * dt if s.mb[i] > 0 else 0.0
        if s.top == "fixed":
            dua[0] = dub[0] = 0.0
        if s.bot == "fixed":
            dua[-1] = dub[-1] = 0.0
        s.dua, s.dub = dua, dub
        s.ua, s.ub = s.ua + dua, s.ub + dub
        s.s_old = s.s.copy()
        s.s = s.s + Z / dt * (dub[:-1] - dua[1:])
        s.q = tuple(q)

    def fragments(s):
        b = [0] + [i for i in range(1, s.N) if not s.joined[i]] + [s.N]
        return list(zip(b[:-1], b[1:]))

    def r(s, top, bot, i):
        if i == top and top > 0:
            p = s.mb[i] * s.dub[i]
        elif i == bot and bot < s.N:
            p = s.ma[i] * s.dua[i]
        else:
            p = s.ma[i] * s.dua[i] + s.mb[i] * s.dub[i]
        return p / s.dt

    def reading(s, top, bot, at_n=False):
        """spb_wave.fragment_h: h_k = Z_k g_k, s_k dt, J' of the fragment top..bot"""
        dt, Z, o = s.dt, s.Z, 0 if at_n else 1
        r = {i: s.r(top, bot, i) for i in range(top, bot + 1)}
        sdt = {k: (s.s_old if at_n else s.s)[k - 1] * dt for k in range(top + 1, bot + 1)}
        eq_t = top > 0 or s.top == "free"
        eq_b = bot < s.N or s.bot == "free"
        lt = 0.5 * s.q[0] if top == 0 and s.top == "free" else 0.0
        lb = 0.5 * s.q[1] if bot == s.N and s.bot == "free" else 0.0
        tr_t = top == 0 and s.top == "transmit" and not eq_b
        tr_b = bot == s.N and s.bot == "transmit" and not eq_t
        eq_t, eq_b = eq_t or tr_t, eq_b or tr_b
        wt, wb = s.w_in()
        eta_t, eta_b = Z[0] * (wt + s.delta()), Z[-1] * (wb + s.delta())
        jp = sum((-1) ** (i - top) * (r[i] + (sdt[i] if i > top else 0.0)) for i in r)
        odd = (bot - top) % 2 == 1
        if odd:
            jp += 2 * lb
        if eq_t and not eq_b and odd:
            jp = -jp - 2 * lt
        if s.rules["odd"] and odd and (tr_t or tr_b):
            out_t, out_b = r[top] - eta_t, r[bot] - eta_b
            if tr_t and tr_b:
                jp = out_t + out_b
            elif tr_b and not eq_t:
                jp += 2 * out_b
            elif tr_t and not eq_b:
                jp += 2 * out_t
        if bot == top:
            return {}, sdt, jp
        hd = {top + 1: 0.0}
        if eq_t and not tr_t:
            hd[top + 1] = r[top] - lt if at_n else r[top] + lt - sdt[top + 1]
        if tr_t:
            hd[top + 1] = r[top] - eta_t if at_n else eta_t - sdt[top + 1]
        for k in range(top + 1, bot):
            hd[k + 1] = r[k] - sdt[k + o] - hd[k]
        if eq_b:
            hu = {bot: (r[bot] - eta_b - sdt[bot] if at_n else eta_b) if tr_b else
                  (r[bot] - sdt[bot] + lb if at_n else r[bot] - lb)}
            for k in range(bot - 1, top, -1):
                hu[k] = r[k] - sdt[k + o] - hu[k + 1]
        if eq_t and eq_b:
            h = {k: 0.5 * (hd[k] + hu[k]) for k in hd}
        elif eq_t:
            h = hd
        elif eq_b:
            h = hu
        else:
            sg = {k: (-1.0) ** (k - top - 1) for k in hd}
            al = -sum(sg[k] * (2 * hd[k] + sdt[k]) / Z[k - 1] for k in hd) / sum(2 / Z[k - 1] for k in hd)
            h = {k: hd[k] + sg[k] * al for k in hd}
        return h, sdt, jp

    def measure(s):
        """e_wave + e_pot + e_wave_g"""
        m = -s.g * np.sum(s.ma * (s.ua - 0.5 * s.dua) + s.mb * (s.ub - 0.5 * s.dub))
        for t, b in s.fragments():
            h, sdt, jp = s.reading(t, b)
            m += sum((h[k] ** 2 + (h[k] + sdt[k]) ** 2) / s.Z[k - 1] for k in h) / s.dt
            m -= 0.5 * s.g * s.dt * jp
        return m

    def rho(s):
        """the zig-zag content at the transmitting ends: reading's incoming - w_in - g dt^2/4"""
        wt, wb = s.w_in()
        fr = s.fragments()
        out = [0.0, 0.0]
        if s.top == "transmit":
            h, sdt, _ = s.reading(*fr[0])
            out[0] = (h[1] + sdt[1]) / s.Z[0] - wt - s.delta()
        if s.bot == "transmit":
            h, sdt, _ = s.reading(*fr[-1])
            out[1] = h[s.N] / s.Z[-1] - wb - s.delta()
        return out

    def work(s, rho_after):
        """w_wave of the step just taken; rho_after: the zig-zag content after it"""
        dt, Z = s.dt, s.Z
        wt, wb = s.w_in()
        if s.rules["rho"]:
            wt, wb = wt + rho_after[0], wb + rho_after[1]
        w = {"free": s.q[0] * s.dub[0] / dt, "fixed": 0.0,
             "transmit": Z[0] * s.dub[0] * (2 * wt - s.dub[0]) / dt}[s.top]
        return w + {"free": -s.q[1] * s.dua[-1] / dt, "fixed": 0.0,
                    "transmit": Z[-1] * s.dua[-1] * (2 * wb - s.dua[-1]) / dt}[s.bot]

    def advance(s, q_prev, q):
        """one intact step and its work; rho read before the step and negated (spb_step)"""
        rho = [-x for x in s.rho()] if s.rules["rho"] else [0.0, 0.0]
        s.step(q_prev, q)
        return s.work(rho)

    def brk(s, i):
        """the admissible break of joined node i (spb_rules_admissible.admissible_breaks)"""
        t, b = [fb for fb in s.fragments() if fb[0] < i < fb[1]][0]
        h, sdt, _ = s.reading(t, b, at_n=True)
        da, db = 2 * (h[i] + sdt[i]) / s.Z[i - 1], 2 * h[i + 1] / s.Z[i]
        dda, ddb = da - s.dua[i], db - s.dub[i]
        s.ua[i] += dda; s.dua[i] = da; s.ub[i] += ddb; s.dub[i] = db
        s.s[i - 1] -= s.Z[i - 1] / s.dt * dda
        s.s[i] += s.Z[i] / s.dt * ddb
        s.joined[i] = False


def start(lat, rng, kind):
    """'unstressed' (at rest, the ends' own velocity 0.7 m/s), or 'consistent': a random state
    every equation reads alike (random intervals, the transmitting ends' incoming ones)"""
    N, Z, dt = lat.N, lat.Z, lat.dt
    if kind == "unstressed":
        du = np.full(N + 1, 0.7 * dt)
        du[[0, -1]] = [0.0 if lat.top == "fixed" else 0.7 * dt, 0.0 if lat.bot == "fixed" else 0.7 * dt]
        lat.set_state(np.zeros(N + 1), du)
        return
    f, g = rng.normal(size=N), rng.normal(size=N)
    wt, wb = lat.w_in()
    if lat.top == "transmit":
        f[0] = wt + lat.delta()
    if lat.bot == "transmit":
        g[-1] = wb + lat.delta()
    u = np.concatenate([[0.0], -np.cumsum(f - g)])
    if lat.bot == "fixed":
        u -= u[-1]
    r = np.zeros(N + 1)
    r[1:N] = Z[1:] * f[1:] + Z[:-1] * g[:-1]
    r[0] = {"free": Z[0] * f[0], "fixed": 0.0, "transmit": rng.normal()}[lat.top]
    r[N] = {"free": Z[-1] * g[-1], "fixed": 0.0, "transmit": rng.normal()}[lat.bot]
    lat.set_state(u, r * dt / (lat.ma + lat.mb))


ENDS = [("fixed", "transmit"), ("transmit", "fixed"), ("free", "transmit"), ("transmit", "free"),
        ("transmit", "transmit")]


def ledger_drift(top, bot, N, g, rules, kind, rng, dt=0.3, steps=60, breaks=()):
    """largest |measure - measure_0 - work| over an intact run with random loads through the
    loaded faces (and the change each break books)"""
    Z = rng.uniform(0.5, 2.0, N)
    lat = Lattice(Z, dt, g, top, bot, (0.7, -0.4), (0.7, 0.7), rules)
    start(lat, rng, kind)
    qs = rng.normal(size=(steps, 2))
    qs[:, 0] *= top != "fixed"
    qs[:, 1] *= bot != "fixed"
    m0, w, worst, booked, q_prev = lat.measure(), 0.0, 0.0, [], np.zeros(2)
    for n in range(steps):
        w += lat.advance(q_prev, qs[n])
        q_prev = qs[n]
        for (at, i) in breaks:
            if at == n:
                before = lat.measure()
                lat.brk(i)
                booked.append(lat.measure() - before)
                m0 += booked[-1]
        worst = max(worst, abs(lat.measure() - m0 - w))
    return worst, booked


def landing(lat):
    """a landing at t^n of the bottom face (spb_contact.land, no shift): the booked change"""
    before = lat.measure()
    new = copy.deepcopy(lat)
    du = new.dua[-1]
    new.dua[-1] = new.dub[-1] = 0.0
    new.ua[-1] -= du; new.ub[-1] = new.ua[-1]
    new.s[-1] += new.Z[-1] / new.dt * du
    new.bot = "fixed"
    return before - new.measure()


def main():
    rng = np.random.default_rng(17)
    print("1. intact ledger, |e_wave + e_pot + e_wave_g - w_wave - const| (lattice units, random "
          "loads; g = 1, dt = 0.3)")
    for kind in ("consistent", "unstressed"):
        for top, bot in ENDS:
            row = []
            for N in (4, 5):
                for rules in (OLD, NEW):
                    row.append(ledger_drift(top, bot, N, 1.0, rules, kind, rng)[0])
            print(f"   {kind:10s} {top:8s} {bot:8s} N=4: old {row[0]:.1e} new {row[1]:.1e};"
                  f"  N=5: old {row[2]:.1e} new {row[3]:.1e}")
    print("   old rules, fixed top / transmitting bottom, N = 5: the error grows with g (x g) and dt:")
    for g in (0.25, 1.0, 4.0):
        print(f"     g = {g}: " + ", ".join(
            f"dt {dt}: {ledger_drift('fixed', 'transmit', 5, g, OLD, 'consistent', np.random.default_rng(3), dt)[0]:.2e}"
            for dt in (0.1, 0.3)))
    print("2. the transmitting end's equation: a static bar standing on a transmitting bottom "
          "(free top, homogeneous):")
    for N in (4, 5):
        Z = np.ones(N); g, dt = 1.0, 0.3
        s1 = Z[0] * dt / 2 * g
        s = s1 + np.arange(N) * Z * dt * g          # s_{k+1} = s_k + m g
        u = np.concatenate([[0.0], -np.cumsum(s * dt / Z)])
        lat = Lattice(Z, dt, g, "free", "transmit", (0.0, s[-1] + Z[-1] * dt * g), (0.0, 0.0))
        lat.set_state(u, np.zeros(N + 1))
        h, sdt, _ = lat.reading(0, N)
        wb = lat.w_in()[1]
        print(f"   N = {N}: free face's incoming interval - w_in = {h[N] / Z[-1] - wb:.6f}, "
              f"g dt^2/4 = {g * dt * dt / 4:.6f}")
    print("3. the zig-zag content rho of an unstressed start (free top, transmitting bottom, "
          "g = 1, dt = 0.3, loads):")
    lat = Lattice(rng.uniform(0.5, 2, 5), 0.3, 1.0, "free", "transmit", (0.0, 0.0), (0.7, 0.7))
    start(lat, rng, "unstressed")
    rhos, q_prev = [lat.rho()[1]], np.zeros(2)
    for n in range(6):
        q = rng.normal(size=2)
        lat.advance(q_prev, q)
        q_prev = q
        rhos.append(lat.rho()[1])
    print("   rho / (g dt^2/4) = " + ", ".join(f"{x / (0.09 / 4):+.12f}" for x in rhos))
    print("4. admissible breaks (change of the measure, should be 0):")
    for top, bot in ENDS:
        for N in (4, 5):
            worst = 0.0
            for i in range(1, N):
                for rules in (NEW,):
                    d, booked = ledger_drift(top, bot, N, 1.0, rules, "unstressed", rng,
                                             breaks=((7, i),))
                    worst = max(worst, abs(booked[0]), d)
            old = max(abs(ledger_drift(top, bot, N, 1.0, OLD, "consistent", rng, breaks=((7, i),))[1][0])
                      for i in range(1, N))
            print(f"   {top:8s} {bot:8s} N={N}: new rules: break and after {worst:.1e}; "
                  f"old rules: break books {old:.1e}")
    print("5. landing of a bar hanging from a transmitting top (booked change, new rules):")
    for N in (3, 4, 5):
        zero, zz = 0.0, 0.0
        for trial in range(20):
            Z = rng.uniform(0.5, 2, N)
            lat = Lattice(Z, 0.3, 1.0, "transmit", "free", tuple(rng.normal(size=2)), (0.4, 0.0))
            start(lat, rng, "consistent")
            for n in range(3):
                lat.advance(np.zeros(2), np.zeros(2))
            zero = max(zero, abs(landing(lat)))
            sg = (-1.0) ** np.arange(N + 1)        # the zig-zag mode u_i = A (-1)^(n+i)
            lat.set_state(lat.ua + 0.05 * sg, lat.dua + 0.1 * sg)
            zz = max(zz, abs(landing(lat)))
        print(f"   N = {N}: rho = 0: {zero:.1e}; with zig-zag content (A = 0.05): up to {zz:.2e} "
              "(either sign: the open part)")


if __name__ == "__main__":
    main()
