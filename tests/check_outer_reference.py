"""Independent check of the outer solar system's reference state.

Integrates the problem the scene's doubles define (the double G, masses,
sqrt(m_i) and mass-weighted initial state, exactly as the scene rounds them)
in x87 long double (64-bit significand, unit round-off 5.4e-20) with numpy,
by a method other than the reference's: the sixth-order triple jump of the
Stormer-Verlet step (9 force evaluations a step), with every position and
velocity update compensated (Kahan), at 2^15 and 2^16 steps over the
scene's default end time.

Prints, for each of the 36 mass-weighted coordinates (q then v, body after
body), the long-double value at 2^16 steps as a pair of doubles `hi lo`
(hi + lo equals it exactly), then the phase-space distance between the two
runs, an estimate of the coarser run's truncation error (a sixth-order
method's error falls 64-fold from 2^15 to 2^16 steps).

Usage: python3 tests/check_outer_reference.py   (about 3 minutes)
"""
import math
import sys

import numpy as np

L = np.longdouble

# The published data (Hairer, Lubich, Wanner, I.2.4), stated here again so
# that the check shares nothing with the crate but the problem; were the
# scene's values to change, its end state would leave this one and the
# harness test comparing the two would fail.
G = 2.95912208286e-4
MASSES = [
    1.00000597682,
    0.000954786104043,
    0.000285583733151,
    0.0000437273164546,
    0.0000517759138449,
    1.0 / 1.3e8,
]
POSITIONS = [
    [0.0, 0.0, 0.0],
    [-3.5023653, -3.8169847, -1.5507963],
    [9.0755314, -3.0458353, -1.6483708],
    [8.3101420, -16.2901086, -7.2521278],
    [11.4707666, -25.7294829, -10.8169456],
    [-15.5387357, -25.2225594, -3.1902382],
]
VELOCITIES = [
    [0.0, 0.0, 0.0],
    [0.00565429, -0.00412490, -0.00190589],
    [0.00168318, 0.00483525, 0.00192462],
    [0.00354178, 0.00137102, 0.00055029],
    [0.00288930, 0.00114527, 0.00039677],
    [0.00276725, -0.00170702, -0.00136504],
]


def period():
    """Jupiter's Kepler period about the Sun, in doubles as the scene has it."""
    mu = G * (MASSES[0] + MASSES[1])
    r = math.sqrt(sum(c * c for c in POSITIONS[1]))
    v = math.sqrt(sum(c * c for c in VELOCITIES[1]))
    a = 1.0 / (2.0 / r - v * v / mu)
    return 2.0 * math.pi * math.sqrt(a * a * a / mu)  # Rust powi(3): (a a) a


def root(n):
    """2^(1/n) in long double, Newton from the double root."""
    y = L(2.0 ** (1.0 / n))
    for _ in range(3):
        y = y - (y**n - L(2)) / (L(n) * y ** (n - 1))
    return y


def weights():
    """The 9 Verlet fractions of the sixth-order triple jump."""
    w = [L(1)]
    for p in (2, 4):
        r = root(p + 1)
        g = L(1) / (L(2) - r)
        w = [f * x for f in (g, -r * g, g) for x in w]
    return w


SQRT_M = np.array([math.sqrt(m) for m in MASSES])  # the doubles the scene uses
GM = L(G) * np.array([L(m) for m in MASSES], dtype=L)


def start():
    q = np.array(POSITIONS, dtype=np.float64) * SQRT_M[:, None]  # one rounding, as the scene
    v = np.array(VELOCITIES, dtype=np.float64) * SQRT_M[:, None]
    s = SQRT_M.astype(L)[:, None]
    return q.astype(L) / s, v.astype(L) / s


def acceleration(r):
    d = r[None, :, :] - r[:, None, :]  # d[i, j] = r_j - r_i
    r2 = (d * d).sum(axis=2)
    np.fill_diagonal(r2, L(1))
    inv3 = L(1) / (r2 * np.sqrt(r2))
    np.fill_diagonal(inv3, L(0))
    return (d * (inv3 * GM[None, :])[:, :, None]).sum(axis=1)


def add(x, carry, increment):
    """Kahan: x + carry + increment, the new rounding kept in carry."""
    y = increment + carry
    t = x + y
    return t, y - (t - x)


def run(steps, t_end):
    r, v = start()
    cr, cv = np.zeros_like(r), np.zeros_like(v)
    h = L(t_end) / L(steps)
    fractions = [w * h for w in weights()]
    half = L(0.5)
    for n in range(steps):
        for tau in fractions:
            r, cr = add(r, cr, v * (tau * half))
            v, cv = add(v, cv, acceleration(r) * tau)
            r, cr = add(r, cr, v * (tau * half))
        if n % 4096 == 0:
            print(f"  {steps} steps: {n}", file=sys.stderr)
    s = SQRT_M.astype(L)[:, None]
    return (r + cr) * s, (v + cv) * s


def main():
    t_end = 2.0 * math.sqrt(2.0) * period()
    w = 2.0 * math.pi / period()
    coarse = run(1 << 15, t_end)
    fine = run(1 << 16, t_end)
    for block in fine:
        for x in block.ravel():
            hi = np.float64(x)
            lo = np.float64(x - L(hi))
            print(f"{float(hi)!r} {float(lo)!r}")
    dq = fine[0] - coarse[0]
    dv = (fine[1] - coarse[1]) / w
    print(f"distance 2^15 to 2^16 steps: {float(np.sqrt((dq * dq).sum() + (dv * dv).sum())):e}")


if __name__ == "__main__":
    main()
