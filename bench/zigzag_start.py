"""Issue 17, "transmitting top, first landing": a start without the lattice's zig-zag content.

A fragment with a transmitting end whose other end gives an equation (a free face, a second
transmitting end) has the zig-zag mode u_i = A (-1)^(n+i) as a neutral mode (eigenvalue -1,
simple). At t^0 (n = 0) the mode adds
    du_i += 2 A (-1)^i,   u_i += A (-1)^i,   s_k += (Z_k/dt) 2 A (-1)^(k-1)
and its reading (from the free face) is f_k = -A (-1)^(n+k), g_k = A (-1)^(n+k): it changes the
zig-zag content rho (the reading's incoming interval at the transmitting end minus
w_in + g dt^2/4) by A (-1)^n at a transmitting top (top node 0) and by A (-1)^(n+N) at a
transmitting bottom (bottom node N). rho is affine in the state and flips sign in every intact
step, so its linear part is the left eigenvector of the mode: A = -rho_top (top) or
A = -(-1)^N rho_bot (bottom) removes exactly the mode's component (the spectral projection),
and rho stays 0. This script checks that on the lattice model of bench/transmit_gravity.py,
measures what the projection changes in the measure, and the first landing's booked change
with and without the projection (python3 bench/zigzag_start.py).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from transmit_gravity import Lattice, landing  # noqa: E402


def project(lat, top, bot):
    """remove the zig-zag mode from the fragment top..bot at t^0 (whole bar here: top = 0,
    bot = N); returns A"""
    rt, rb = lat.rho()
    N = lat.N
    if lat.top == "transmit" and lat.bot == "transmit":
        A = -rt * 2 * lat.Z[0] / (lat.Z[0] + lat.Z[-1])
    elif lat.top == "transmit":
        A = -rt
    else:
        A = -(-1.0) ** N * rb
    sg = np.zeros(N + 1)
    sg[top:bot + 1] = (-1.0) ** np.arange(top, bot + 1)
    lat.set_state(lat.ua + A * sg, lat.dua + 2 * A * sg)
    return A


def e_wave(lat):
    """the reading's energy alone (no potential, no gravity term)"""
    e = 0.0
    for t, b in lat.fragments():
        h, sdt, _ = lat.reading(t, b)
        e += sum((h[k] ** 2 + (h[k] + sdt[k]) ** 2) / lat.Z[k - 1] for k in h) / lat.dt
    return e


def unstressed(lat, v, strain=0.0):
    """at rest in stress, moving at v (+ strain (x - x_c), a free face its cell's mean)"""
    N, dt = lat.N, lat.dt
    x = np.concatenate([[0.0], np.cumsum(lat.Z / lat.Z)])          # unit cells (a dt = 1)
    m = lat.ma + lat.mb
    vel = v + strain * (x - np.sum(m * x) / np.sum(m))
    if lat.top == "free":
        vel[0] += strain * 0.5
    if lat.bot == "free":
        vel[-1] -= strain * 0.5
    lat.vf = (vel[0], vel[-1])
    lat.set_state(np.zeros(N + 1), vel * dt)


def main():
    rng = np.random.default_rng(5)
    g, dt = 1.0, 0.3
    d4 = g * dt * dt / 4
    print("1. unstressed starts (random layered Z, velocity 0.7), rho / (g dt^2/4) before and after"
          " the projection, and over 40 intact steps after it:")
    for top, bot in (("transmit", "free"), ("free", "transmit"), ("transmit", "transmit")):
        for N in (4, 5):
            lat = Lattice(rng.uniform(0.5, 2, N), dt, g, top, bot, (0.0, 0.0))
            unstressed(lat, 0.7)
            before = lat.rho()
            m0, e0 = lat.measure(), e_wave(lat)
            A = project(lat, 0, N)
            after = lat.rho()
            dm = lat.measure() - m0
            worst = 0.0
            for n in range(40):
                lat.advance(np.zeros(2), np.zeros(2))
                worst = max(worst, *np.abs(lat.rho()))
            print(f"   {top:8s} {bot:8s} N={N}: rho before {before[0] / d4:+.3f} {before[1] / d4:+.3f}, "
                  f"A / (g dt^2/4) = {A / d4:+.3f}, after {max(map(abs, after)) / d4:.1e}, "
                  f"40 steps {worst / d4:.1e}; measure changed by {dm / e0:+.3e} of e_wave, "
                  f"(g dt/v)^2/4 = {(g * dt / 0.7) ** 2 / 4:.3e}")
    print("2. a strain rate c (per cell) with g = 0 (transmitting top, free bottom): rho / (c dx dt/4)")
    for N in (4, 5):
        lat = Lattice(np.ones(N), dt, 0.0, "transmit", "free", (0.0, 0.0))
        unstressed(lat, 0.7, strain=0.2)
        print(f"   N = {N}: rho_top = {lat.rho()[0] / (0.2 * 1.0 * dt / 4):+.4f}")
    print("3. the first landing (bar hanging from a transmitting top, free bottom face read as "
          "landing at t^n after 1..29 steps), |booked change| / e_wave, 200 random unstressed "
          "starts each:")
    for N in (3, 4, 5, 8):
        worst = [0.0, 0.0]
        for trial in range(200):
            Z = rng.uniform(0.5, 2, N)
            for k, proj in enumerate((False, True)):
                r2 = np.random.default_rng(trial)
                lat = Lattice(Z, dt, g, "transmit", "free", (r2.normal(), 0.0))
                unstressed(lat, r2.normal())
                lat.vf = (lat.vf[0], 0.0)
                if proj:
                    project(lat, 0, N)
                for n in range(r2.integers(1, 30)):
                    lat.advance(np.zeros(2), np.zeros(2))
                scale = e_wave(lat)
                b = landing(lat)
                worst[k] = max(worst[k], abs(b) / scale)
        print(f"   N = {N}: unprojected up to {worst[0]:.2e}, projected up to {worst[1]:.2e}")


if __name__ == "__main__":
    main()
