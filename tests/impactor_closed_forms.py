#!/usr/bin/env python3
"""Closed forms for a striking mass on an elastic bar (issue 33): the reference the `&impactor`
end is tested against.

Conventions (those of spallbar, doc/method.md): x runs from the struck face into the bar,
u along +x, **stress positive in compression**, gravity g along +x (towards the bar: the mass
falls onto it). A uniform bar: density rho, wave speed c, impedance Z = rho c, area A, length L,
round trip T = 2 L / c. The mass M (kg; kg/m^2 with A = 1) strikes with V0 (along +x); sigma0 =
Z V0 is the stress a rigid face moving at V0 sends into the bar at rest, alpha = rho A L / M the
ratio of the bar's mass to the striker's.

d'Alembert. In the bar u = F(t - x/c) + G(t + x/c); with sigma = -E u_x and v = u_t, the down-going
part carries sigma_d = Z F' = Z v_d, the up-going part sigma_u = -Z G' = -Z v_u, so sigma =
sigma_d + sigma_u and v = (sigma_d - sigma_u) / Z. At the struck face f(t) = sigma_d(0, t) is the
outgoing wave, h(t) = sigma_u(0, t) the incoming one. The far end returns the outgoing wave T later:
h(t) = R f(t - T) with R = +1 (fixed end, v = 0), R = -1 (free end, sigma = 0), R = 0 (transmitting
end, a semi-infinite bar); the bar is at rest and unstressed for t < 0 (f = 0 for t < 0).

The mass. M V' = -A sigma_face + M g. In rigid contact the face moves with the mass,
V = (f - h) / Z, so sigma_face = f + h = Z V + 2 h: the mass couples to the incoming
characteristic only. It pushes only: the contact ends when sigma_face would become negative; a
free face has sigma_face = 0, i.e. f = -h, and moves at -2 h / Z. With gravity the bar is taken in
its static state (stress 0 at the struck face, rho g x below it for a fixed or transmitting far
end); its dynamic part then obeys the homogeneous wave equation and everything above holds for it
(a free far end falls with the mass: take g = 0, the relative motion).

Every function takes plain floats (times may be numpy arrays where said). Root finding is
bracketed bisection to the last bit (relative 1e-15 and better on the abscissa)."""
import math

import numpy as np

__all__ = ["Bar", "laguerre", "sv_polynomial", "SaintVenant", "FreeFarEnd", "Transmitting",
           "CushionTransmitting", "gap_closing", "constant_velocity_face_stress",
           "constant_velocity_fixed_end_stress", "bisect_root", "phi_moment"]


class Bar:
    """A uniform bar: density rho [kg/m^3], wave speed c [m/s], area A [m^2], length L [m]
    (math.inf for a semi-infinite bar). Z = rho c, T = 2 L / c (inf when L is)."""

    def __init__(self, density, wave_speed, area=1.0, length=math.inf):
        self.rho = float(density)
        self.c = float(wave_speed)
        self.area = float(area)
        self.length = float(length)
        self.z = self.rho * self.c
        self.transit = 2.0 * self.length / self.c

    def mass(self):
        """rho A L [kg]."""
        return self.rho * self.area * self.length


# ----------------------------------------------------------------------------------------
# small numerical helpers


def bisect_root(fun, a, b, fa=None, fb=None, max_iter=400):
    """A root of fun in [a, b] where fun(a), fun(b) have opposite signs (or one is 0), by
    bisection until the bracket has no representable midpoint: relative 1e-16 on the abscissa."""
    fa = fun(a) if fa is None else fa
    fb = fun(b) if fb is None else fb
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0):
        raise ValueError("bisect_root: no sign change in [%r, %r]" % (a, b))
    for _ in range(max_iter):
        m = 0.5 * (a + b)
        if m <= a or m >= b:
            break
        fm = fun(m)
        if fm == 0.0:
            return m
        if (fm > 0.0) == (fa > 0.0):
            a, fa = m, fm
        else:
            b, fb = m, fm
    return a if abs(fa) < abs(fb) else b


def first_crossing(fun, a, b, samples=400, downward=True, vectorized=False):
    """The first point in (a, b] where fun crosses 0 (downward: from > 0 to <= 0; else from < 0
    to >= 0), from `samples` equal sub-intervals and bisect_root; None if there is none.
    vectorized: fun takes the array of samples at once (and floats in the bisection)."""
    xs = np.linspace(a, b, samples + 1)
    fs = np.asarray(fun(xs), dtype=float) if vectorized else np.array([fun(x) for x in xs])
    hit = (fs[:-1] > 0.0) & (fs[1:] <= 0.0) if downward else (fs[:-1] < 0.0) & (fs[1:] >= 0.0)
    i = np.flatnonzero(hit)
    if i.size == 0:
        return None
    i = int(i[0])
    scalar = (lambda x: float(np.asarray(fun(np.array([x]))).ravel()[0])) if vectorized else fun
    return bisect_root(scalar, xs[i], xs[i + 1], fs[i], fs[i + 1])


_GL_X, _GL_W = np.polynomial.legendre.leggauss(32)


def gauss_integral(fun, a, b, pieces=4):
    """Integral of a smooth fun over [a, b] by 32-point Gauss-Legendre on `pieces` equal parts:
    exact to round-off for the polynomial-times-exponential integrands used here (degree < 64,
    and an exponential whose rate times the part length is O(1))."""
    total = 0.0
    edges = np.linspace(a, b, pieces + 1)
    for lo, hi in zip(edges[:-1], edges[1:]):
        x = 0.5 * (hi - lo) * _GL_X + 0.5 * (hi + lo)
        total += 0.5 * (hi - lo) * float(np.dot(_GL_W, fun(x)))
    return total


def _phi(k, z):
    """phi_k(z) = integral_0^1 e^{(1 - s) z} s^{k-1} / (k-1)! ds (phi_0 = e^z), complex z; the
    Taylor series sum z^j / (j + k)! for |z| < 1, else phi_{j+1} = (phi_j - 1/j!) / z."""
    z = complex(z)
    if abs(z) < 1.0:
        term = 1.0 / math.factorial(k)
        total = term
        for j in range(1, 60):
            term = term * z / (j + k)
            total += term
            if abs(term) < 1e-18 * abs(total):
                break
        return total
    val = complex(math.e ** z.real) * complex(math.cos(z.imag), math.sin(z.imag))
    for j in range(k):
        val = (val - 1.0 / math.factorial(j)) / z
    return val


def phi_moment(p, q, z):
    """m(p, q, z) = integral_0^1 s^p (1 - s)^q e^{z s} ds for p in (0, 1), complex z, accurate
    for small |z| too: m(0, q, z) = q! phi_{q+1}(z) (substitute s -> 1 - s in phi's integral),
    m(1, q, z) = m(0, q, z) - m(0, q + 1, z) (s = 1 - (1 - s))."""
    if p == 0:
        return math.factorial(q) * _phi(q + 1, z)
    if p == 1:
        return phi_moment(0, q, z) - phi_moment(0, q + 1, z)
    raise ValueError("phi_moment: p must be 0 or 1")


class _ExpPoly:
    """g(t) = const + sum_i Re[(a_i + b_i t) e^{lam_i t}] (complex a, b, lam allowed): its value,
    its first and second integrals from 0, and its integral over [t1, t1 + h], all with the
    phi-moment functions so that no digit is lost for small lam t or small h."""

    def __init__(self, const, terms):
        self.const = float(const)
        self.terms = [(complex(a), complex(b), complex(lam)) for a, b, lam in terms]

    def value(self, t):
        t = float(t)
        v = self.const
        for a, b, lam in self.terms:
            v += ((a + b * t) * np.exp(lam * t)).real
        return v

    def integral(self, t):
        """integral_0^t g: (a + b s) e^{lam s} gives a t m(0,0,lam t) + b t^2 m(1,0,lam t)."""
        t = float(t)
        v = self.const * t
        for a, b, lam in self.terms:
            v += (a * t * phi_moment(0, 0, lam * t) + b * t * t * phi_moment(1, 0, lam * t)).real
        return v

    def integral2(self, t):
        """integral_0^t integral_0^s g = integral_0^t (t - r) g(r) dr: a t^2 m(0,1,.) +
        b t^3 m(1,1,.)."""
        t = float(t)
        v = 0.5 * self.const * t * t
        for a, b, lam in self.terms:
            v += (a * t ** 2 * phi_moment(0, 1, lam * t) +
                  b * t ** 3 * phi_moment(1, 1, lam * t)).real
        return v

    def step_integral(self, t1, h):
        """integral over [t1, t1 + h]: h e^{lam t1} [(a + b t1) m(0,0,lam h) + b h m(1,0,lam h)]."""
        v = self.const * h
        for a, b, lam in self.terms:
            v += (h * np.exp(lam * t1) * ((a + b * t1) * phi_moment(0, 0, lam * h) +
                                          b * h * phi_moment(1, 0, lam * h))).real
        return v


# ----------------------------------------------------------------------------------------
# 1. Saint-Venant: rigid mass on a bar with a fixed far end


def laguerre(n, y):
    """[L_0(y), ..., L_n(y)], the Laguerre polynomials, by (j + 1) L_{j+1} = (2j + 1 - y) L_j -
    j L_{j-1} (y a float or a numpy array)."""
    y = np.asarray(y, dtype=float)
    out = [np.ones_like(y)]
    if n >= 1:
        out.append(1.0 - y)
    for j in range(1, n):
        out.append(((2 * j + 1 - y) * out[j] - j * out[j - 1]) / (j + 1))
    return out


def sv_polynomial(k, alpha):
    """Coefficients (ascending powers of xi = x - k) of P_k in Saint-Venant's outgoing wave, by the
    recursion the mass's equation gives (see SaintVenant): P_0 = 1, P_k(0) = 1,
    P_k' = P_{k-1}' - 4 alpha P_{k-1}. (P_1 = 1 - 4 alpha xi, P_2 = 1 - 8 alpha xi + 8 alpha^2 xi^2,
    ...; P_k(xi) = L_k(4 alpha xi), the Laguerre polynomial, since L_k' = L_{k-1}' - L_{k-1}.)"""
    p = np.polynomial.Polynomial([1.0])
    for _ in range(k):
        dp = p.deriv() - 4.0 * alpha * p
        p = dp.integ() + 1.0          # integ() is 0 at xi = 0
    return p.coef


class SaintVenant:
    """A rigid mass M striking (velocity V0, rigid contact, gap 0) a bar at rest whose far end is
    FIXED; optionally gravity g along +x with the bar in its static state.

    Derivation. x = t / T; the fixed end gives h(x) = f(x - 1). With V = (f - h)/Z in
    M V' = -A (f + h) + M g and Z A T / M = 2 alpha:

        f_x + 2 alpha f = h_x - 2 alpha h + 2 alpha sigma_g,     sigma_g = M g / A,

    with f(0+) = sigma0 (the face takes V0 at once) and V continuous, so f jumps with h: by
    sigma0 at every x = k. Write f = sum_j [sigma0 phi_j + sigma_g psi_j](x - j) H(x - j) (H the
    step); term by term phi_j' + 2 alpha phi_j = phi_{j-1}' - 2 alpha phi_{j-1}, phi_j(0) = 1. With
    phi_j = e^{-2 alpha xi} P_j(xi) this is P_j' = P_{j-1}' - 4 alpha P_{j-1}, P_j(0) = 1
    (sv_polynomial), solved by P_j(xi) = L_j(4 alpha xi) (L_j' = L_{j-1}' - L_{j-1}, L_j(0) = 1).
    So on k <= x < k + 1 (the issue's s_{k+1}):

        f(x) = sigma0 sum_{j=0..k} e^{-2 alpha (x-j)} L_j(4 alpha (x - j))        (g = 0)

    s_1 = sigma0 e^{-2 alpha x}; s_2 = s_1 + sigma0 e^{-2 alpha (x-1)} [1 - 4 alpha (x-1)];
    s_3 = s_2 + sigma0 e^{-2 alpha (x-2)} [1 - 8 alpha (x-2) + 8 alpha^2 (x-2)^2]: the issue's forms
    hold.
    Gravity adds psi_0 = 1 - e^{-2 alpha xi} (the source), psi_j(0) = 0 and the same recursion, so
    psi_j = (-1)^j + e^{-2 alpha xi} Q_j(4 alpha xi), Q_j = -L_j + 2 sum_{i=1..j} (-1)^{i+1} L_{j-i}
    (each L_{j-i} solves the recursion; the constants fix Q_j(0) = -(-1)^j).

    What holds, precisely, while the mass is in contact (0 <= t <= t_r):
      * contact stress sigma_c(t) = f(t) + f(t - T) (compression positive; f = 0 for t < 0); it
        jumps by 2 sigma0 at t = T, 2T, ... (the reflected front doubles on the mass) and is
        continuous between;
      * mass velocity V = (f(t) - f(t - T)) / Z, displacement X = (Phi(t) - Phi(t - T)) / Z,
        Phi(t) = int_0^t f; momentum A int sigma_c = M (V0 - V) + M g t gives the exact recursion
        Phi(t) = (M / (Z A)) (sigma0 - f(t) + f(t - T)) + M g t / A - Phi(t - T);
      * fixed-end stress sigma_L(t) = sigma_d + sigma_u = f(t - T/2) + f(t - T/2) = 2 f(t - T/2)
        for t <= t_r + T/2 (0 before T/2). Later the outgoing wave is that of a free face,
        f(t) = -f(t - T) for t > t_r (while the mass does not strike again), so the fixed end sees
        the last period of the contact wave with alternating sign.
    The contact ends at t_r, the first zero of sigma_c (not before T: sigma_c > 0 on [0, T)). On
    [T, 2T), g = 0: sigma_c = sigma0 e^{-2 alpha xi} [2 + e^{-2 alpha} - 4 alpha xi], xi = x - 1, so
    t_r / T = 1 + (2 + e^{-2 alpha}) / (4 alpha) when that is below 2 (alpha > 0.57859...;
    alpha = 1: 1.5338338208); smaller alpha release later (root finding). Stresses and the limits
    of f at the jumps are right limits.

    After the release the face is free and driven by the trapped wave, and it can strike the mass
    again (g = 0; found with impactor_reference.py over 12 T): alpha = 1 at 2.1246 T (released at
    2.1628 T, the mass leaves at -0.6989 V0 instead of -0.6876 V0), alpha = 0.25 at 3.0011 T
    (released at 3.3286 T, -0.9593 V0); alpha = 0.5 leaves for good at -0.9252 V0. The statements
    about later times hold until such a second blow."""

    def __init__(self, bar, mass, velocity, gravity=0.0):
        self.bar = bar
        self.m = float(mass)
        self.v0 = float(velocity)
        self.g = float(gravity)
        self.alpha = bar.mass() / self.m
        self.period = bar.transit
        self.sigma0 = bar.z * self.v0
        self.sigma_g = self.m * self.g / bar.area
        self._release = None

    # the outgoing wave and its derivative, x = t / T
    def _wave(self, x, derivative=False):
        x = np.atleast_1d(np.asarray(x, dtype=float))
        a = self.alpha
        out = np.zeros_like(x)
        if x.size == 0:
            return out
        kmax = int(np.floor(np.max(x))) if np.max(x) >= 0.0 else -1
        for j in range(kmax + 1):
            on = x >= j
            if not np.any(on):
                continue
            xi = x[on] - j
            y = 4.0 * a * xi
            lag = laguerre(j, y)
            e = np.exp(-2.0 * a * xi)
            q = -lag[j] + 2.0 * sum((-1) ** (i + 1) * lag[j - i] for i in range(1, j + 1))
            if not derivative:
                out[on] += self.sigma0 * e * lag[j] + self.sigma_g * ((-1) ** j + e * q)
            else:
                # d/dx [e^{-y/2} P(y)] = 4 alpha e^{-y/2} (P'(y) - P(y)/2); L_j' = -sum_{i<j} L_i
                dlag = [-sum(lag[i] for i in range(m)) if m else np.zeros_like(y)
                        for m in range(j + 1)]
                dq = -dlag[j] + 2.0 * sum((-1) ** (i + 1) * dlag[j - i] for i in range(1, j + 1))
                out[on] += 4.0 * a * e * (self.sigma0 * (dlag[j] - 0.5 * lag[j]) +
                                          self.sigma_g * (dq - 0.5 * q))
        return out

    def outgoing(self, t):
        """f(t), the wave the face sends into the bar during contact [Pa] (array in, array out)."""
        return self._wave(np.asarray(t, dtype=float) / self.period)

    def outgoing_rate(self, t):
        """df/dt [Pa/s]."""
        return self._wave(np.asarray(t, dtype=float) / self.period, derivative=True) / self.period

    def contact_stress(self, t):
        """sigma_c(t) = f(t) + f(t - T), valid for 0 <= t <= t_r [Pa]."""
        t = np.asarray(t, dtype=float)
        return self.outgoing(t) + self.outgoing(t - self.period)

    def fixed_end_stress(self, t):
        """sigma_L(t) = 2 f(t - T/2), valid for t <= t_r + T/2 [Pa]."""
        return 2.0 * self.outgoing(np.asarray(t, dtype=float) - 0.5 * self.period)

    def velocity(self, t):
        """V(t) = (f(t) - f(t - T)) / Z [m/s]."""
        t = np.asarray(t, dtype=float)
        return (self.outgoing(t) - self.outgoing(t - self.period)) / self.bar.z

    def wave_integral(self, t):
        """Phi(t) = int_0^t f [Pa s] for t <= t_r (array in, array out), by the momentum
        recursion Phi(t) = tau (sigma0 - f(t) + f(t - T)) + M g t / A - Phi(t - T), tau = M/(Z A),
        unrolled: Phi(t) = sum_j (-1)^j [tau (sigma0 - f(t_j) + f(t_j - T)) + M g t_j / A], t_j =
        t - j T >= 0. No quadrature."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        tau = self.m / (self.bar.z * self.bar.area)
        out = np.zeros_like(t)
        T = self.period
        j = 0
        while np.any(t - j * T > 0.0):
            tj = t - j * T
            on = tj > 0.0
            term = tau * (self.sigma0 - self.outgoing(tj[on]) + self.outgoing(tj[on] - T)) + \
                self.m * self.g * tj[on] / self.bar.area
            out[on] += (-1) ** j * term
            j += 1
        return out

    def displacement(self, t):
        """X(t) = (Phi(t) - Phi(t - T)) / Z, the mass's (and the face's) displacement [m]."""
        t = np.asarray(t, dtype=float)
        return (self.wave_integral(t) - self.wave_integral(t - self.period)) / self.bar.z

    def release_time(self, horizon=40):
        """t_r: the first zero of sigma_c, searched interval by interval [kT, (k+1)T) (sigma_c
        is continuous inside), 400 samples each, then bisection to the last bit [s]; math.inf
        when the contact lasts beyond `horizon` periods (a mass put on the bar at rest under
        gravity stays longer)."""
        if self._release is None:
            T = self.period
            self._release = math.inf
            for k in range(1, horizon):
                lo = k * T * (1.0 + 1e-15)
                hi = (k + 1) * T * (1.0 - 1e-15)
                r = first_crossing(self.contact_stress, lo, hi, 400, vectorized=True)
                if r is not None:
                    self._release = r
                    break
        return self._release

    def _extremum(self, a, b, sign=1.0):
        """(value, where) of the largest sign * f over [a, b] (sign = -1: the smallest f): the
        candidates are the ends, the right limits at the jumps kT and the interior zeros of f'
        (where sign * f' goes from > 0 to <= 0, by bisection on f')."""
        T = self.period
        cands = [a, b]
        for k in range(int(math.floor(a / T)), int(math.floor(b / T)) + 1):
            lo, hi = max(a, k * T), min(b, (k + 1) * T * (1.0 - 1e-15))
            if hi <= lo:
                continue
            cands.append(lo)
            xs = np.linspace(lo, hi, 801)
            d = sign * self.outgoing_rate(xs)
            for i in range(800):
                if d[i] > 0.0 >= d[i + 1]:
                    cands.append(bisect_root(lambda s: sign * float(self.outgoing_rate(s)[0]),
                                             xs[i], xs[i + 1], d[i], d[i + 1]))
        vals = sign * self.outgoing(np.array(cands))
        i = int(np.argmax(vals))
        return sign * float(vals[i]), float(cands[i])

    def peak_fixed_end_stress(self):
        """(peak_contact, t_peak, peak_all): the largest fixed-end stress 2 max f(s) over the
        contact's wave, s in [0, t_r], reached at t_peak = s + T/2; and the largest over all later
        times too, 2 max(max f on [0, t_r], max -f on [t_r - T, t_r]) (after the release the trapped
        wave repeats the last period of f with alternating sign, while the mass does not strike
        again)."""
        tr = self.release_time()
        pk, s = self._extremum(0.0, tr)
        low, _ = self._extremum(tr - self.period, tr, -1.0)
        return 2.0 * pk, s + 0.5 * self.period, 2.0 * max(pk, -low)

    def bar_energy(self, t):
        """Wave energy in the bar at t <= t_r [J]: (A / Z) int_{t-T}^{t} f^2 (the down-going wave
        holds f over [t - T/2, t], the reflected one f over [t - T, t - T/2]; rho v^2/2 +
        sigma^2/(2E) = (sigma_d^2 + sigma_u^2)/(rho c^2)). Gauss-Legendre between the jumps."""
        T = self.period
        a, b = max(0.0, t - T), t
        total = 0.0
        edges = [a] + [k * T for k in range(int(a / T) + 1, int(b / T) + 1) if a < k * T < b] + [b]
        for lo, hi in zip(edges[:-1], edges[1:]):
            total += gauss_integral(lambda s: self.outgoing(s) ** 2, lo, hi, 8)
        return self.bar.area / self.bar.z * total

    def bar_momentum(self, t):
        """Momentum of the bar at t <= t_r [kg m/s]: rho A int v dx = A [int_{t-T/2}^{t} f -
        int_{t-T}^{t-T/2} f] = A [Phi(t) - 2 Phi(t - T/2) + Phi(t - T)]."""
        T = self.period
        phi = self.wave_integral(np.array([t, t - 0.5 * T, t - T]))
        return self.bar.area * float(phi[0] - 2.0 * phi[1] + phi[2])

    def at_release(self):
        """What the contact leaves: release time, the mass's velocity and displacement, the bar's
        momentum and wave energy, the mass's kinetic energy (a dict). At t_r sigma_c = 0, so
        V(t_r) = -2 f(t_r - T) / Z; energy: M V0^2/2 = M V^2/2 - M g X + E_bar."""
        tr = self.release_time()
        return {"t_release": tr,
                "v_mass": float(self.velocity(tr)[0]),
                "x_mass": float(self.displacement(tr)[0]),
                "p_bar": self.bar_momentum(tr),
                "e_bar": self.bar_energy(tr),
                "e_mass": 0.5 * self.m * float(self.velocity(tr)[0]) ** 2}

    def step_means(self, dt, nsteps):
        """(1/dt) int sigma_c over [n dt, (n+1) dt], n = 0..nsteps-1, for steps that end by t_r
        (Gauss-Legendre per step, split at the jumps kT; divided by the rounded width
        (n+1) dt - n dt)."""
        T = self.period
        out = np.empty(nsteps)
        for n in range(nsteps):
            a, b = n * dt, (n + 1) * dt
            edges = [a] + [k * T for k in range(int(a / T) + 1, int(b / T) + 1) if a < k * T < b]
            edges.append(b)
            s = 0.0
            for lo, hi in zip(edges[:-1], edges[1:]):
                s += gauss_integral(self.contact_stress, lo, hi, 1)
            out[n] = s / (b - a)
        return out


# ----------------------------------------------------------------------------------------
# 2. free far end


class FreeFarEnd:
    """A rigid mass M strikes (V0, gap 0, g = 0) a bar at rest whose far end is FREE.

    Derivation. Until T nothing returns: sigma_c = f = sigma0 e^{-2 alpha t/T} (the transmitting
    solution). At T the free end's reflection h(t) = -f(t - T) arrives: a jump of -sigma0 in h, so
    (V continuous) a jump of -2 sigma0 in sigma_c, to sigma0 (e^{-2 alpha} - 2) < 0: the contact
    would pull, so the mass releases exactly at t_r = T (for every alpha). Then
      * mass: V(T) = f(T-)/Z = V0 e^{-2 alpha}, momentum M V0 e^{-2 alpha}, energy
        (M V0^2/2) e^{-4 alpha};
      * bar: momentum M V0 (1 - e^{-2 alpha}) (= A int_0^T f), mean velocity V0 (1 - e^{-2 alpha}) /
        alpha, energy (A/Z) int_0^T f^2 = (M V0^2/2)(1 - e^{-4 alpha}): momentum and energy are
        shared exactly (no loss in a rigid contact);
      * no second blow: after T the free face moves at -2 h / Z, which repeats 2 V0 e^{-2 alpha
        (t/T - k)} >= 2 V0 e^{-2 alpha} > V(T) with period T, so the face runs away from the mass.
    """

    def __init__(self, bar, mass, velocity):
        self.bar = bar
        self.m = float(mass)
        self.v0 = float(velocity)
        self.alpha = bar.mass() / self.m
        self.period = bar.transit
        self.sigma0 = bar.z * self.v0

    def contact_stress(self, t):
        """sigma_c(t) = sigma0 e^{-2 alpha t/T} for 0 <= t < T, 0 after [Pa]."""
        t = np.asarray(t, dtype=float)
        return np.where(t < self.period, self.sigma0 * np.exp(-2.0 * self.alpha * t / self.period),
                        0.0)

    def at_release(self):
        """Release time T, the mass's velocity and energy, the bar's momentum, energy and mean
        velocity (a dict)."""
        e2 = math.exp(-2.0 * self.alpha)
        return {"t_release": self.period,
                "v_mass": self.v0 * e2,
                "e_mass": 0.5 * self.m * self.v0 ** 2 * e2 * e2,
                "p_bar": self.m * self.v0 * (-math.expm1(-2.0 * self.alpha)),
                "e_bar": 0.5 * self.m * self.v0 ** 2 * (-math.expm1(-4.0 * self.alpha)),
                "v_bar_mean": self.v0 * (-math.expm1(-2.0 * self.alpha)) / self.alpha}


# ----------------------------------------------------------------------------------------
# 3. transmitting far end (semi-infinite bar), with gravity (5.)


class Transmitting:
    """A rigid mass M on a semi-infinite bar (h = 0): M V' = -A Z V + M g, so with
    tau = M / (Z A), V_inf = g tau (the speed at which the bar carries the weight M g away):

        V(t) = V_inf + (V0 - V_inf) e^{-t/tau},
        sigma(t) = Z V = sigma_g + (sigma0 - sigma_g) e^{-t/tau}

    (sigma_g = M g / A; g = 0: sigma = sigma0 e^{-Z A t / M}), X(t) = V_inf t + (V0 - V_inf) tau
    (1 - e^{-t/tau}). With V0 >= 0 and g >= 0 sigma stays > 0: the contact never ends, and after the
    transient the bar carries the steady force M g. With g < 0 (the mirrored case: a mass striking
    the bottom face upwards, gravity pulling it back) sigma falls to 0 at t_r = tau ln(1 + sigma0 /
    |sigma_g|), where V = 0: the mass releases and falls back, the face stays (release_time).
    Step means: (1/dt) int_{n dt}^{(n+1) dt} sigma = sigma_g + (sigma0 - sigma_g) e^{-n dt/tau}
    (tau/dt)(1 - e^{-dt/tau}) (with expm1: no digit lost)."""

    def __init__(self, bar, mass, velocity, gravity=0.0):
        self.bar = bar
        self.m = float(mass)
        self.v0 = float(velocity)
        self.g = float(gravity)
        self.tau = self.m / (bar.z * bar.area)
        self.v_inf = self.g * self.tau
        self.sigma0 = bar.z * self.v0
        self.sigma_g = self.m * self.g / bar.area

    def stress(self, t):
        """Face stress [Pa]."""
        t = np.asarray(t, dtype=float)
        return self.sigma_g + (self.sigma0 - self.sigma_g) * np.exp(-t / self.tau)

    def velocity(self, t):
        """Mass (= face) velocity [m/s]."""
        t = np.asarray(t, dtype=float)
        return self.v_inf + (self.v0 - self.v_inf) * np.exp(-t / self.tau)

    def displacement(self, t):
        """Mass (= face) displacement [m]."""
        t = np.asarray(t, dtype=float)
        return self.v_inf * t - (self.v0 - self.v_inf) * self.tau * np.expm1(-t / self.tau)

    def stress_integral(self, t1, t2):
        """int_{t1}^{t2} sigma = sigma_g (t2 - t1) + (sigma0 - sigma_g) tau e^{-t1/tau}
        (1 - e^{-(t2 - t1)/tau}) [Pa s] (no difference of large numbers)."""
        h = t2 - t1
        return self.sigma_g * h + (self.sigma0 - self.sigma_g) * self.tau * \
            math.exp(-t1 / self.tau) * -math.expm1(-h / self.tau)

    def release_time(self):
        """tau log1p(sigma0 / |sigma_g|) when g < 0, else math.inf [s]."""
        if self.g >= 0.0:
            return math.inf
        return self.tau * math.log1p(self.sigma0 / -self.sigma_g)

    def step_means(self, dt, nsteps):
        """(1/dt) int sigma over [n dt, (n+1) dt], n = 0..nsteps-1 [Pa] (before a release)."""
        n = np.arange(nsteps, dtype=float)
        return self.sigma_g + (self.sigma0 - self.sigma_g) * np.exp(-n * dt / self.tau) * \
            (-np.expm1(-dt / self.tau)) * self.tau / dt


# ----------------------------------------------------------------------------------------
# 4. cushioned mass on a semi-infinite bar, with gravity and repeated blows (5.)


class CushionTransmitting:
    """A mass M with a linear cushion k (N/m) strikes (V0, the cushion just touching at t = 0) a
    semi-infinite bar; gravity g along +x optional.

    The bar is a dashpot: the face stress is Z v_face (h = 0), so the cushion force F = k delta
    (delta = X - u_face, the cushion's compression) drives the face at v_face = F / (Z A): the mass,
    the spring and the dashpot Z A are in series (a Maxwell element under the mass). With
    M X'' = -F + M g and F' = k (X' - F/(Z A)):

        F'' + 2 zeta w0 F' + w0^2 F = w0^2 M g,    F(0) = 0,  F'(0) = k V0,
        w0 = sqrt(k/M),  zeta = sqrt(k M) / (2 Z A).

    Under-damped (zeta < 1, w = w0 sqrt(1 - zeta^2), s = zeta w0):
        F = M g + e^{-s t} [-M g cos w t + (k V0 - s M g)/w sin w t];
    critically damped (zeta = 1): F = M g + (-M g + (k V0 - w0 M g) t) e^{-w0 t};
    over-damped (lam_1,2 = -s +- w0 sqrt(zeta^2 - 1)): F = M g + a e^{lam1 t} + b e^{lam2 t},
        a + b = -M g, lam1 a + lam2 b = k V0.
    g = 0 gives k V0 e^{-s t} sin(w t)/w, k V0 t e^{-w0 t}, k V0 e^{-s t} sinh(w' t)/w'.

    Separation: the cushion cannot pull, so the blow ends at the first zero t_s of F after 0. Under-
    damped with g = 0: t_s = pi / w, and the mass leaves at V(t_s) = F'(t_s)/k = -V0 e^{-zeta pi /
    sqrt(1 - zeta^2)} (the face stops at once: F = 0 and h = 0). Critically and over-damped F > 0
    for all t > 0 (F - M g has at most one zero): no separation (F -> M g, or -> 0+ when g = 0).
    With g > 0, under-damped: t_s from bisection when the first minimum of F is below 0, else none.

    Also V(t) = V0 + g t - (1/M) int_0^t F, X(t) = V0 t + g t^2/2 - (1/M) int int F, u_face(t) =
    (1/(Z A)) int_0^t F, X - u_face = F / k; step means (1/(A dt)) int F; all integrals exact
    (_ExpPoly). Repeated blows (g > 0): after t_s the face rests (h = 0, sigma = 0), the mass flies
    up at V_s < 0 and comes back to the same point after 2 |V_s| / g with speed |V_s|: blow k + 1 is
    this closed form again with V0 = |V_s(blow k)| (blows())."""

    def __init__(self, bar, mass, velocity, cushion, gravity=0.0):
        self.bar = bar
        self.m = float(mass)
        self.v0 = float(velocity)
        self.k = float(cushion)
        self.g = float(gravity)
        self.w0 = math.sqrt(self.k / self.m)
        self.zeta = math.sqrt(self.k * self.m) / (2.0 * bar.z * bar.area)
        self.force_form = self._force_form(self.v0)

    def regime(self):
        """'under', 'critical' or 'over' (critical when |zeta - 1| < 1e-12)."""
        if abs(self.zeta - 1.0) < 1e-12:
            return "critical"
        return "under" if self.zeta < 1.0 else "over"

    def _force_form(self, v0):
        mg = self.m * self.g
        s = self.zeta * self.w0
        kv = self.k * v0
        reg = self.regime()
        if reg == "under":
            w = self.w0 * math.sqrt(1.0 - self.zeta ** 2)
            c1, c2 = -mg, (kv - s * mg) / w
            # c1 cos + c2 sin = Re[(c1 - i c2) e^{i w t}]
            return _ExpPoly(mg, [(complex(c1, -c2), 0.0, complex(-s, w))])
        if reg == "critical":
            a = -mg
            b = kv - self.w0 * mg
            return _ExpPoly(mg, [(a, b, -self.w0)])
        r = self.w0 * math.sqrt(self.zeta ** 2 - 1.0)
        l1, l2 = -s + r, -s - r
        # a + b = -mg, l1 a + l2 b = kv
        a = (kv + l2 * mg) / (l1 - l2)
        b = -mg - a
        return _ExpPoly(mg, [(a, 0.0, l1), (b, 0.0, l2)])

    def force(self, t):
        """Cushion force F(t) [N] (valid until separation)."""
        return np.vectorize(self.force_form.value)(np.asarray(t, dtype=float))

    def stress(self, t):
        """Face stress F / A [Pa]."""
        return self.force(t) / self.bar.area

    def velocity(self, t):
        """Mass velocity [m/s]."""
        f = np.vectorize(self.force_form.integral)(np.asarray(t, dtype=float))
        return self.v0 + self.g * np.asarray(t, dtype=float) - f / self.m

    def displacement(self, t):
        """Mass displacement [m]."""
        t = np.asarray(t, dtype=float)
        f2 = np.vectorize(self.force_form.integral2)(t)
        return self.v0 * t + 0.5 * self.g * t * t - f2 / self.m

    def face_displacement(self, t):
        """Face displacement [m]."""
        f = np.vectorize(self.force_form.integral)(np.asarray(t, dtype=float))
        return f / (self.bar.z * self.bar.area)

    def separation_time(self):
        """t_s, the first zero of F after 0 [s], or math.inf (critically and over-damped, or a
        blow under gravity too soft to lift off)."""
        if self.regime() != "under":
            return math.inf
        w = self.w0 * math.sqrt(1.0 - self.zeta ** 2)
        if self.g == 0.0:
            return math.pi / w
        period = 2.0 * math.pi / w
        r = first_crossing(self.force_form.value, 1e-9 * period, 1.5 * period, 3000)
        return math.inf if r is None else r

    def step_means(self, dt, nsteps):
        """(1/(A dt)) int F over [n dt, (n+1) dt] [Pa] (before separation)."""
        return np.array([self.force_form.step_integral(n * dt, dt) for n in range(nsteps)]) / (
            self.bar.area * dt)

    def blows(self, count, gap=0.0):
        """Repeated blows under gravity (g > 0, under-damped): a list of dicts (t_impact,
        v_impact, t_separation, v_separation, u_face at separation). The first impact closes a
        gap d with V0 (gap_closing); each later one follows a ballistic flight of 2 |V_s| / g."""
        if self.g <= 0.0:
            raise ValueError("blows needs gravity")
        t0, v = gap_closing(gap, self.v0, self.g) if gap > 0.0 else (0.0, self.v0)
        u = 0.0
        out = []
        for _ in range(count):
            blow = CushionTransmitting(self.bar, self.m, v, self.k, self.g)
            ts = blow.separation_time()
            if not math.isfinite(ts):
                out.append({"t_impact": t0, "v_impact": v, "t_separation": math.inf})
                break
            vs = v + self.g * ts - blow.force_form.integral(ts) / self.m
            u += blow.force_form.integral(ts) / (self.bar.z * self.bar.area)
            out.append({"t_impact": t0, "v_impact": v, "t_separation": t0 + ts,
                        "v_separation": vs, "u_face": u})
            t0 = t0 + ts + 2.0 * abs(vs) / self.g
            v = abs(vs)
        return out


# ----------------------------------------------------------------------------------------
# 5. gravity: the gap


def gap_closing(gap, velocity, gravity):
    """(t, V): a mass starting gap d above a face at rest with V0 (along +x) under g reaches it at
    t = 2 d / (V0 + sqrt(V0^2 + 2 g d)) (the root of d = V0 t + g t^2 / 2, written without
    cancellation) with V = sqrt(V0^2 + 2 g d); g = 0: t = d / V0."""
    d, v0, g = float(gap), float(velocity), float(gravity)
    v = math.sqrt(v0 * v0 + 2.0 * g * d)
    return 2.0 * d / (v0 + v), v


# ----------------------------------------------------------------------------------------
# 6. M -> infinity: the constant-velocity end


def constant_velocity_face_stress(t, bar, velocity, far):
    """Face stress of an end moving at V0 for ever (Saint-Venant's struck end, M -> infinity;
    spallbar's 'velocity' end), on a bar at rest [Pa]. f = Z V0 + h with h = R f(t - T):
      far = 'transmit': Z V0;
      far = 'fixed':  f = (k + 1) Z V0 on [kT, (k+1)T), sigma = (2k + 1) Z V0 (it grows: the bar is
                      compressed without limit); the fixed end sees 2 f(t - T/2) = 2 (k + 1) Z V0;
      far = 'free':   f = Z V0, 0, Z V0, 0, ...; sigma = +Z V0, -Z V0, +Z V0, ... (a bilateral
                      end; a mass, which pushes only, releases at T with every alpha).
    Saint-Venant's f tends to it as alpha -> 0 (e^{-2 alpha xi} L_j(4 alpha xi) -> 1)."""
    t = np.asarray(t, dtype=float)
    s0 = bar.z * float(velocity)
    if far == "transmit":
        return np.where(t >= 0.0, s0, 0.0)
    k = np.floor(t / bar.transit)
    if far == "fixed":
        return np.where(t >= 0.0, (2.0 * k + 1.0) * s0, 0.0)
    if far == "free":
        return np.where(t >= 0.0, np.where(k % 2 == 0, s0, -s0), 0.0)
    raise ValueError("far must be 'transmit', 'fixed' or 'free'")


def constant_velocity_fixed_end_stress(t, bar, velocity):
    """Fixed-end stress under a constant-velocity struck end: 2 (k + 1) Z V0 for
    t - T/2 in [kT, (k+1)T), 0 before T/2 [Pa]."""
    t = np.asarray(t, dtype=float) - 0.5 * bar.transit
    k = np.floor(t / bar.transit)
    return np.where(t >= 0.0, 2.0 * (k + 1.0) * bar.z * float(velocity), 0.0)
