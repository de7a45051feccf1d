#!/usr/bin/env python3
"""An independent numerical reference for a striking mass on a uniform elastic bar (issue 33):
the method of characteristics for the bar, a spectral solution of the mass's equations between
characteristic arrivals, unilateral contact, a cushion, gravity and repeated blows.

It shares no formula with impactor_closed_forms.py but the physics (conventions there: x into the
bar, compression positive, g along +x towards the bar).

The bar. A uniform bar (Z = rho c, area A, round trip T = 2 L / c) at rest (its dynamic part; with
gravity its static state, stress 0 at the struck face) carries d'Alembert's two waves. The only
unknown is the wave the struck face sends out, f(t); the far end returns it as the incoming wave
h(t) = R f(t - T) (R = +1 fixed, -1 free, 0 transmitting: T = inf). At the face, stress
sigma = f + h and velocity v_face = (f - h) / Z, i.e. sigma = Z v_face + 2 h: given h, the face is a
dashpot Z A in series with the incoming characteristic.

The face's partner, in one of three modes:
  * rigid contact:   M V' = -A sigma + M g, v_face = V           => M V' = -A (Z V + 2 h) + M g;
  * cushion contact: F = k delta, delta = X - u_face (> 0), M V' = -F + M g,
                     v_face = (F / A - 2 h) / Z, delta' = V - v_face (solved for F / (A Z) and V,
                     both velocities: a balanced system);
  * free:            sigma = 0, v_face = -2 h / Z; the mass flies, V' = g.
Events: rigid contact ends when sigma would become negative, a cushion's when delta reaches 0 (it
cannot pull); a free mass strikes when X - u_face reaches 0 (with a cushion: it touches). X is the
mass's position measured so that X = u_face when it touches (X(0) = -gap).

The numerical method. Time is cut into pieces at every arrival of a discontinuity of h (every piece
boundary of f, shifted by T) and at most dt_max long (dt_max = T/m, so that the arrivals of the
regular cuts fall on cuts). On a piece h is smooth and known (a Chebyshev series of an earlier
piece of f), and the mode's equations are linear: they are solved in integral form, y = y_a +
int (B y + b(t)) dt, collocated at n + 1 Chebyshev points with the exact Chebyshev integration
matrix (spectral accuracy: the error falls like rate^n dt_max^n / n!, at the default n = 24 and
rate dt_max <= 1 far below round-off; the test compares degrees 24 and 36). An event is located on
the piece's Chebyshev interpolant by bisection to the last bit and the piece is solved again up to
it. No time step, no quadrature of the delay: the error is round-off plus the truncated series."""
import bisect
import math

import numpy as np
from numpy.polynomial import chebyshev as cheb

__all__ = ["Reference"]

_GL = np.polynomial.legendre.leggauss(24)     # exact for degree <= 47 (the pieces' n <= 46)


class _Cheb:
    """Chebyshev-Lobatto points on [-1, 1] (increasing), values -> coefficients, and the
    integration matrix (values -> values of the integral from -1)."""

    def __init__(self, n):
        self.n = n
        self.x = -np.cos(np.pi * np.arange(n + 1) / n)
        self.x[0], self.x[-1] = -1.0, 1.0
        self.to_coef = np.linalg.inv(cheb.chebvander(self.x, n))
        icoef = np.zeros((n + 2, n + 1))
        for k in range(n + 1):
            e = np.zeros(n + 1)
            e[k] = 1.0
            icoef[:, k] = cheb.chebint(e, lbnd=-1)
        self.integ = cheb.chebvander(self.x, n + 1) @ icoef @ self.to_coef


class _Piece:
    """One piece [a, b] in one mode; Chebyshev coefficients (on [a, b] mapped to [-1, 1]) of the
    face stress, the outgoing and incoming waves, the mass's velocity and position, the face's
    displacement."""

    def __init__(self, a, b, mode, coefs):
        self.a, self.b, self.mode, self.c = a, b, mode, coefs

    def s(self, t):
        return (2.0 * np.asarray(t, dtype=float) - self.a - self.b) / (self.b - self.a)

    def value(self, name, t):
        return cheb.chebval(self.s(t), self.c[name])

    def integral(self, name, t1, t2):
        """int_{t1}^{t2} of the named quantity (t1, t2 in [a, b], arrays alike): Gauss-Legendre
        with as many points as the interpolant needs (exact for its degree, and no difference of
        two large antiderivative values)."""
        t1 = np.asarray(t1, dtype=float)
        t2 = np.asarray(t2, dtype=float)
        half = 0.5 * (t2 - t1)
        nodes = half[..., None] * _GL[0] + (0.5 * (t1 + t2))[..., None]
        return np.sum(self.value(name, nodes) * _GL[1], axis=-1) * half


class Reference:
    """The striking-mass problem solved piecewise (see the module docstring).

    Parameters (SI): density, wave_speed, area, length (inf for 'transmit'), far ('fixed' |
    'free' | 'transmit'), mass M, velocity V0, gravity g, gap, cushion k (0 = rigid), degree n of
    the Chebyshev pieces, per_transit: pieces per T at least. Run with run(t_end); then read
    the quantities at any t (right limits at jumps), integrals over intervals, the events list
    [(t, 'impact' | 'release')], the bar's wave energy and momentum."""

    def __init__(self, density, wave_speed, area, length, far, mass, velocity, gravity=0.0,
                 gap=0.0, cushion=0.0, degree=24, per_transit=8):
        self.rho, self.c, self.area = float(density), float(wave_speed), float(area)
        self.far = far
        self.z = self.rho * self.c
        self.m, self.v0, self.g = float(mass), float(velocity), float(gravity)
        self.k = float(cushion)
        self.refl = {"fixed": 1.0, "free": -1.0, "transmit": 0.0}[far]
        self.length = float(length) if far != "transmit" else math.inf
        self.period = 2.0 * self.length / self.c if far != "transmit" else math.inf
        # the fastest rate of the modes' equations sets the piece length
        rate = self.z * self.area / self.m
        if self.k > 0.0:
            rate = max(rate, self.k / (self.z * self.area), math.sqrt(self.k / self.m))
        if math.isfinite(self.period):
            m = max(per_transit, int(math.ceil(self.period * rate)))
            self.dt_max = self.period / m
        else:
            self.dt_max = 1.0 / rate
        self.ch = _Cheb(degree)
        self.pieces = []
        self.starts = []          # piece starts, ascending (for lookup and the arrivals)
        self.events = []
        # state at the current time
        self.t = 0.0
        self.x = -float(gap)      # mass position; touches when x = u_face
        self.v = self.v0
        self.u = 0.0              # face displacement
        if gap > 0.0:
            self.mode = "free"
        else:
            self.mode = "cushion" if self.k > 0.0 else "contact"
            self.events.append((0.0, "impact"))

    # -- lookup -------------------------------------------------------------------------
    def _piece_at(self, t):
        i = bisect.bisect_right(self.starts, t) - 1
        return self.pieces[max(0, min(i, len(self.pieces) - 1))]

    def _incoming(self, tt, t_mid):
        """h at the times tt of one piece (whose middle is t_mid): R f(tt - T) from the earlier
        piece holding t_mid - T; 0 before anything returns."""
        if self.refl == 0.0 or t_mid - self.period < 0.0:
            return np.zeros_like(tt)
        p = self._piece_at(t_mid - self.period)
        return self.refl * p.value("f", tt - self.period)

    def _next_arrival(self, t):
        """The first time after t at which a discontinuity of h arrives: a piece start of f
        (or the start t = 0 of the bar's motion) plus T."""
        if not math.isfinite(self.period):
            return math.inf
        tol = 1e-13 * self.period
        cands = self.starts + [self.t]
        i = bisect.bisect_right(cands, t - self.period + tol)
        return cands[i] + self.period if i < len(cands) else math.inf

    # -- one piece in one mode ------------------------------------------------------------
    def _solve(self, a, b, mode):
        """Values at the Chebyshev points of [a, b] of every quantity, starting from the current
        state, in the given mode (a dict of arrays)."""
        ch = self.ch
        tt = a + 0.5 * (b - a) * (ch.x + 1.0)
        q = 0.5 * (b - a) * ch.integ
        h = self._incoming(tt, 0.5 * (a + b))
        one = np.ones_like(tt)
        n1 = len(tt)
        if mode == "contact":
            beta = self.z * self.area / self.m
            lhs = np.eye(n1) + beta * q
            rhs = self.v * one + q @ (self.g * one - 2.0 * self.area / self.m * h)
            vel = np.linalg.solve(lhs, rhs)
            x = self.x + q @ vel
            u = self.u + (x - self.x)
            sig = self.z * vel + 2.0 * h
            delta = np.zeros_like(tt)
        elif mode == "cushion":
            # unknowns in velocity units (a balanced system): w = sigma / Z and V;
            # w' = (k/(A Z)) (V - v_face), v_face = w - 2 h / Z;  V' = g - (A Z / M) w
            kz = self.k / (self.z * self.area)
            beta = self.z * self.area / self.m
            lhs = np.block([[np.eye(n1) + kz * q, -kz * q], [beta * q, np.eye(n1)]])
            w0 = self.k * (self.x - self.u) / (self.area * self.z)
            rhs = np.concatenate([w0 * one + kz * (q @ (2.0 * h / self.z)),
                                  self.v * one + q @ (self.g * one)])
            sol = np.linalg.solve(lhs, rhs)
            w, vel = sol[:n1], sol[n1:]
            sig = self.z * w
            delta = self.area * sig / self.k
            u = self.u + q @ (w - 2.0 * h / self.z)
            x = self.x + q @ vel
        else:
            s = tt - a
            vel = self.v + self.g * s
            x = self.x + self.v * s + 0.5 * self.g * s * s
            u = self.u + q @ (-2.0 * h / self.z)
            sig = np.zeros_like(tt)
            delta = np.zeros_like(tt)
        return {"sigma": sig, "h": h, "f": sig - h, "v": vel, "x": x, "u": u, "delta": delta,
                "gap": x - u}

    def _coefs(self, vals):
        return {k: self.ch.to_coef @ v for k, v in vals.items()}

    def _event_function(self, mode):
        """(name, downward): the quantity whose crossing of 0 ends the mode."""
        return {"contact": ("sigma", True), "cushion": ("delta", True),
                "free": ("gap", False)}[mode]

    def _find_event(self, a, b, coefs, mode, samples=96):
        """The first crossing in (a, b] of the mode's event function (bisection on its
        Chebyshev interpolant), or None."""
        name, down = self._event_function(mode)
        c = coefs[name]
        s = np.linspace(-1.0, 1.0, samples + 1)
        vals = cheb.chebval(s, c)
        for i in range(1, samples + 1):
            lo_v, hi_v = vals[i - 1], vals[i]
            hit = (lo_v > 0.0 >= hi_v) if down else (lo_v < 0.0 <= hi_v)
            if not hit:
                continue
            lo, hi = s[i - 1], s[i]
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                fm = cheb.chebval(mid, c)
                if (fm > 0.0) == (lo_v > 0.0) and fm != 0.0:
                    lo = mid
                else:
                    hi = mid
            te = a + 0.5 * (b - a) * (hi + 1.0)
            if te - a > 1e-14 * max(abs(a), b - a):
                return te
        return None

    def _start_switch(self, b):
        """Whether the current mode must change at once at the current time (the right limit of
        h decides): rigid contact whose stress would be tensile, a cushion at zero compression
        opening, a free mass touching the face and approaching it."""
        tt = np.array([self.t])
        h = self._incoming(tt, 0.5 * (self.t + b))[0]
        approach = self.v + 2.0 * h / self.z        # V - v_face of a free face
        if self.mode == "contact":
            return self.z * self.v + 2.0 * h < 0.0
        if self.mode == "cushion":
            return self.x - self.u <= 0.0 and approach < 0.0
        return self.x - self.u >= 0.0 and approach > 0.0

    def _switch(self):
        """Change the mode at the current time; a rigid contact glues the face to the mass (their
        positions agree to round-off at the event: the face takes the mass's)."""
        if self.mode == "free":
            self.mode = "cushion" if self.k > 0.0 else "contact"
            self.events.append((self.t, "impact"))
        else:
            self.mode = "free"
            self.events.append((self.t, "release"))
        if self.k == 0.0:
            self.u = self.x

    def run(self, t_end, max_pieces=200000):
        """Advance to t_end."""
        guard = 0
        checked = False      # an event just decided the new mode: no second look at its start
        while self.t < t_end * (1.0 - 1e-15):
            guard += 1
            if guard > max_pieces:
                raise RuntimeError("Reference: too many pieces")
            b = min(self.t + self.dt_max, t_end, self._next_arrival(self.t))
            if not checked and self._start_switch(b):
                self._switch()
                checked = True
                continue
            checked = False
            vals = self._solve(self.t, b, self.mode)
            coefs = self._coefs(vals)
            te = self._find_event(self.t, b, coefs, self.mode)
            switch = te is not None
            if switch:
                b = te
                vals = self._solve(self.t, b, self.mode)
                coefs = self._coefs(vals)
            self.pieces.append(_Piece(self.t, b, self.mode, coefs))
            self.starts.append(self.t)
            self.t = b
            self.v, self.x, self.u = vals["v"][-1], vals["x"][-1], vals["u"][-1]
            if switch:
                self._switch()
                checked = True
        return self

    # -- reading ----------------------------------------------------------------------------
    def value(self, name, t):
        """A quantity ('sigma', 'f', 'h', 'v', 'x', 'u', 'delta') at the times t (array)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        idx = np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty_like(t)
        for i in np.unique(idx):
            on = idx == i
            out[on] = self.pieces[i].value(name, t[on])
        return out

    def integral(self, name, t1, t2):
        """int_{t1}^{t2} of a quantity, piece by piece."""
        return float(self.step_integrals(name, np.array([t1]), np.array([t2]))[0])

    def step_integrals(self, name, lo, hi):
        """int over [lo_j, hi_j] of a quantity for arrays lo, hi (ascending intervals), piece by
        piece with Gauss-Legendre on each part."""
        out = np.zeros(len(lo))
        for p in self.pieces:
            j0 = np.searchsorted(hi, p.a, side="right")
            j1 = np.searchsorted(lo, p.b, side="left")
            if j1 <= j0:
                continue
            a = np.maximum(lo[j0:j1], p.a)
            b = np.minimum(hi[j0:j1], p.b)
            ok = b > a
            out[j0:j1][ok] += p.integral(name, a[ok], b[ok])
        return out

    def square_integral(self, name, t1, t2):
        """int_{t1}^{t2} of the square of a quantity (Gauss-Legendre of degree 2n + 1 per piece:
        exact for the square of the degree-n interpolant)."""
        xg, wg = np.polynomial.legendre.leggauss(self.ch.n + 2)
        total = 0.0
        i = max(0, bisect.bisect_right(self.starts, t1) - 1)
        while i < len(self.pieces) and self.pieces[i].a < t2:
            p = self.pieces[i]
            lo, hi = max(t1, p.a), min(t2, p.b)
            if hi > lo:
                tt = 0.5 * (hi - lo) * xg + 0.5 * (hi + lo)
                total += 0.5 * (hi - lo) * float(np.dot(wg, p.value(name, tt) ** 2))
            i += 1
        return total

    def step_means(self, name, dt, nsteps):
        """(1/dt) int over [n dt, (n+1) dt] of a quantity, n = 0..nsteps-1. Divided by the width
        of the interval as rounded, (n+1) dt - n dt, not by dt: they differ by n times round-off
        (3e-13 of the mean after 5000 steps), the mean over the rounded interval does not."""
        n = np.arange(nsteps, dtype=float)
        lo, hi = n * dt, (n + 1.0) * dt
        return self.step_integrals(name, lo, hi) / (hi - lo)

    def bar_energy(self, t):
        """The bar's (dynamic) wave energy at t [J]: (A/Z) int f^2 over the outgoing wave still in
        the bar, [t - T, t] for a finite bar (a reflection keeps |f|), [0, t] for a semi-infinite
        one."""
        lo = 0.0 if not math.isfinite(self.period) else max(0.0, t - self.period)
        return self.area / self.z * self.square_integral("f", lo, t)

    def bar_momentum(self, t):
        """The bar's (dynamic) momentum at t [kg m/s]: A [int_{t-T/2}^t f - R int_{t-T}^{t-T/2} f]
        (v = (sigma_d - sigma_u)/Z along the bar, rho A / Z = A / c)."""
        if not math.isfinite(self.period):
            return self.area * self.integral("f", 0.0, t)
        half = max(0.0, t - 0.5 * self.period)
        down = self.integral("f", half, t)
        up = self.integral("f", max(0.0, t - self.period), half)
        return self.area * (down - self.refl * up)

    def mass_energy(self, t):
        """The mass's kinetic and gravity energy and the cushion's, relative to the start [J]."""
        v = self.value("v", t)[0]
        x = self.value("x", t)[0]
        e = 0.5 * self.m * v * v - self.m * self.g * (x - self.value("x", 0.0)[0])
        p = self._piece_at(t)
        if p.mode == "cushion":
            d = p.value("delta", t)
            e += 0.5 * self.k * float(d) ** 2
        return e
