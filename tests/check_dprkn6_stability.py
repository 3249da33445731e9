#!/usr/bin/env python3
"""The one-step matrix of Dormand and Prince's RKN6(4)6FD (and of Nystrom's
fourth-order method) on the oscillator x'' = -x, exactly, from the published
coefficients: the figures that tests/harness/stability.rs checks the crate's
stability study against.

Method. With w0 = 1, step h = z and p = h v, a Nystrom step on x'' = -x is
linear in (q, p): the scaled stages K_i = h^2 k_i solve the lower-triangular
system (I + z^2 A) K = -z^2 (q 1 + p c), and q' = q + p + b_bar . K,
p' = p + b . K. Solving it for (q, p) = (1, 0) and (0, 1) by sympy's exact
linear solve gives the matrix M(z) in (q, h v) as polynomials in w = z^2 with
coefficients in Q(sqrt(8581)); det M and trace M do not depend on the
scaling of v, so they are those of the map on (q, v). Nothing of the crate's
stepper is used: only the tableau, typed here from the published closed
forms in r = sqrt(8581).

What it prints: the polynomials det M - 1 and trace M in w (20 digits), the
positive roots of det M - 1, and at z = 0.1, 0.5, 1, 2, 3 the spectral radius
rho(z) - 1 (growth per step) and rho^(2 pi / z) - 1 (per period) in 40-digit
arithmetic; then the stable window of DPRKN6 above z = 5 (Jury's
conditions det <= 1, |trace| <= 1 + det), and Nystrom's det M - 1, whose
leading term is negative (a damped map).

Run: python3 tests/check_dprkn6_stability.py   (needs sympy and mpmath; a second)
"""

import mpmath as mp
import sympy as sp

mp.mp.dps = 40
w = sp.symbols("w")  # w = z^2
R = sp.Rational


def dprkn6():
    """RKN6(4)6FD: nodes c, matrix A (h^2 coefficients), b_bar, b."""
    r = sp.sqrt(8581)
    c = [0, (209 - r) / 900, (209 - r) / 450, (209 + r) / 450, R(9, 10), 1]
    bb = [R(329, 4212), 0,
          (84119543 + 366727 * r) / 409622616,
          (84119543 - 366727 * r) / 409622616,
          R(200, 17901), 0]
    a = [
        [0] * 6,
        [(26131 - 209 * r) / 810000, 0, 0, 0, 0, 0],
        [(26131 - 209 * r) / 607500, (26131 - 209 * r) / 303750, 0, 0, 0, 0],
        [(980403512254 + 7781688431 * r) / 11694469921875,
         -(1262884486208 + 15385481287 * r) / 11694469921875,
         (7166233891441 + 78694563299 * r) / 46777879687500, 0, 0, 0],
        [-9 * (329260 + 3181 * r) / 27040000,
         27 * (35129 + 3331 * r) / 13520000,
         -27 * (554358343 + 31040327 * r) / 464060480000,
         153 * (8555257 - 67973 * r) / 2745920000, 0, 0],
        list(bb),  # first same as last: the sixth stage is the new position
    ]
    b = [R(329, 4212), 0,
         (389225579 + 96856 * r) / 1024056540,
         (389225579 - 96856 * r) / 1024056540,
         R(2000, 17901), R(1, 20)]
    return c, a, bb, b


def nystrom4():
    """Nystrom's three-stage fourth-order method."""
    c = [0, R(1, 2), 1]
    a = [[0, 0, 0], [R(1, 8), 0, 0], [0, R(1, 2), 0]]
    return c, a, [R(1, 6), R(1, 3), 0], [R(1, 6), R(2, 3), R(1, 6)]


def one_step_matrix(c, a, bb, b):
    """M(w) on (q, h v), from the stage equations by a linear solve."""
    s = len(c)
    system = sp.eye(s) + w * sp.Matrix(a)
    columns = []
    for q, p in ((1, 0), (0, 1)):
        rhs = sp.Matrix([-w * (q + c[i] * p) for i in range(s)])
        k = system.LUsolve(rhs)
        qn = q + p + sum(bb[j] * k[j] for j in range(s))
        pn = p + sum(b[j] * k[j] for j in range(s))
        columns.append((sp.expand(qn), sp.expand(pn)))
    (m11, m21), (m12, m22) = columns
    return m11, m12, m21, m22


def coefficients(poly):
    """Coefficients of a polynomial in w, constant term first, simplified."""
    p = sp.Poly(poly, w)
    return [sp.radsimp(x) for x in reversed(p.all_coeffs())]


def as_mp(x):
    return mp.mpf(str(sp.N(x, 60)))


def evaluate(cs, z):
    x = z * z
    return sum(cf * x ** j for j, cf in enumerate(cs))


def radius(det, trace):
    disc = trace * trace / 4 - det
    return mp.sqrt(det) if disc < 0 else abs(trace) / 2 + mp.sqrt(disc)


def report(name, table):
    m11, m12, m21, m22 = one_step_matrix(*table)
    det = coefficients(sp.expand(m11 * m22 - m12 * m21 - 1))
    trace = coefficients(sp.expand(m11 + m22))
    print(f"{name}: det M - 1 = sum_j d_j z^(2j):")
    for j, x in enumerate(det):
        if x != 0:
            print(f"    d_{j} = {sp.N(x, 20)}   ({x})")
    print(f"{name}: trace M = sum_j t_j z^(2j):")
    for j, x in enumerate(trace):
        print(f"    t_{j} = {sp.N(x, 20)}")
    dm = [as_mp(x) for x in det]
    tm = [as_mp(x) for x in trace]
    low = min(j for j, x in enumerate(dm) if x != 0)
    top = max(j for j, x in enumerate(dm) if x != 0)
    print(f"{name}: leading term of det M - 1: {mp.nstr(dm[low], 20)} z^{2 * low}")
    # det M - 1 = w^low (d_low + d_(low+1) w + ..): the roots of the bracket
    bracket = list(reversed(dm[low : top + 1]))
    roots = mp.polyroots(bracket, maxsteps=200, extraprec=200) if len(bracket) > 1 else []
    positive = [mp.sqrt(x.real) for x in roots if abs(x.imag) < 1e-30 and x.real > 0]
    print(f"{name}: z > 0 where det M = 1:", [mp.nstr(x, 15) for x in positive])
    return dm, tm, positive


if __name__ == "__main__":
    dm, tm, roots = report("DPRKN6", dprkn6())
    print("DPRKN6: growth at z (rho - 1 per step, rho^(2 pi/z) - 1 per period):")
    for z in ("0.1", "0.5", "1", "2", "3"):
        z = mp.mpf(z)
        d = 1 + evaluate(dm, z)
        t = evaluate(tm, z)
        rho = radius(d, t)
        kind = "complex" if t * t / 4 < d else "real"
        print(f"    z = {mp.nstr(z, 3)}: det - 1 = {mp.nstr(d - 1, 12)}, "
              f"rho - 1 = {mp.nstr(rho - 1, 12)}, "
              f"per period {mp.nstr(mp.power(rho, 2 * mp.pi / z) - 1, 12)} "
              f"({kind} eigenvalues)")

    # the stable window: det <= 1 from the root of det - 1 on, until
    # |trace| = 1 + det
    edge = roots[0]
    upper = mp.findroot(lambda z: abs(evaluate(tm, z)) - 2 - evaluate(dm, z), edge + mp.mpf("0.04"))
    mid = (edge + upper) / 2
    d = 1 + evaluate(dm, mid)
    print(f"DPRKN6: stable on [{mp.nstr(edge, 12)}, {mp.nstr(upper, 12)}] "
          f"(at its middle det - 1 = {mp.nstr(d - 1, 6)}, "
          f"rho - 1 = {mp.nstr(radius(d, evaluate(tm, mid)) - 1, 6)})")

    dn, _, _ = report("Nystrom4", nystrom4())
