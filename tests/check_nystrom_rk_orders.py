#!/usr/bin/env python3
"""Checks the explicit Runge-Kutta-Nystrom tables of src/scheme/nystrom_rk.rs
against every Nystrom order condition, exactly, from their published
rationals (DPRKN8 and its embedded solution).

Method: the one of refine_nystrom_coefficients.py, whose series machinery
this imports. One step of the method is applied to power series in h on a
nonlinear q'' = a(q) (D = 2, a force with every monomial up to degree 7 and
pseudo-random coefficients, four initial points): the stages are
K_i = a(q0 + c_i h v0 + h^2 sum_j a_ij K_j), the new state
q0 + h v0 + h^2 sum b_bar_j K_j and v0 + h sum b_j K_j, all on series. The
coefficients of h^k of method minus exact flow vanish for every force and
initial point exactly when the local error is O(h^(k+1)), so an order-p
method prints zeros (rounding of 60-digit arithmetic) through h^p and a
nonzero h^(p+1). The rationals are converted once to 60 digits; the rows'
sums c_i^2/2 are checked in exact fractions.

Run: python3 tests/check_nystrom_rk_orders.py   (needs mpmath; seconds)
"""

import os
import sys
from fractions import Fraction as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import refine_nystrom_coefficients as series  # noqa: E402
from mpmath import mpf  # noqa: E402

D = series.D


def step(c, a, b_bar, b, q0, v0, n):
    """One Nystrom step on series truncated to n terms."""
    k = []
    for i in range(len(c)):
        stage = [[q0[d]] + [mpf(0)] * (n - 1) for d in range(D)]
        for d in range(D):
            stage[d][1] += c[i] * v0[d]
            for j in range(i):
                for m in range(n - 2):
                    stage[d][m + 2] += a[i][j] * k[j][d][m]
        k.append(series.force(stage, n))
    q = [[q0[d], v0[d]] + [mpf(0)] * (n - 2) for d in range(D)]
    v = [[v0[d]] + [mpf(0)] * (n - 1) for d in range(D)]
    for j in range(len(c)):
        for d in range(D):
            for m in range(n - 2):
                q[d][m + 2] += b_bar[j] * k[j][d][m]
            for m in range(n - 1):
                v[d][m + 1] += b[j] * k[j][d][m]
    return q, v


def defects(c, a, b_bar, b, degree):
    """max |h^k coefficient of method minus exact|, k = 0..degree."""
    n = degree + 1
    out = [mpf(0)] * n
    for q0, v0 in series.STARTS:
        qe, ve = series.exact(q0, v0, n)
        qm, vm = step(c, a, b_bar, b, q0, v0, n)
        for m in range(n):
            for d in range(D):
                out[m] = max(out[m], abs(qm[d][m] - qe[d][m]), abs(vm[d][m] - ve[d][m]))
    return out


def mp(row):
    return [mpf(x.numerator) / x.denominator for x in row]


def check(name, c, a, b_bar, b, order):
    for i, row in enumerate(a):
        assert sum(row) == c[i] ** 2 / 2, f"{name}: row {i} does not sum to c^2/2"
    d = defects(mp(c), [mp(r) for r in a], mp(b_bar), mp(b), order + 1)
    print(f"{name} (order {order}): max |h^k defect|, k = 0..{order + 1}:",
          " ".join(f"{float(x):.1e}" for x in d))
    ok = all(x < mpf(10) ** -50 for x in d[:order + 1]) and d[order + 1] > mpf(10) ** -20
    print("   ", "order exactly", order if ok else "NOT as claimed")
    return ok


if __name__ == "__main__":
    # Dormand, El-Mikkawy & Prince (1987), RKN8(6), nine stages
    c = [F(0), F(1, 20), F(1, 10), F(3, 10), F(1, 2), F(7, 10), F(9, 10), F(1), F(1)]
    a = [[F(0)] * 9 for _ in range(9)]
    a[1][:1] = [F(1, 800)]
    a[2][:2] = [F(1, 600), F(1, 300)]
    a[3][:3] = [F(9, 200), F(-9, 100), F(9, 100)]
    a[4][:4] = [F(-66701, 197352), F(28325, 32892), F(-2665, 5482), F(2170, 24669)]
    a[5][:5] = [F(227015747, 304251000), F(-54897451, 30425100), F(12942349, 10141700),
                F(-9499, 304251), F(539, 9250)]
    a[6][:6] = [F(-1131891597, 901789000), F(41964921, 12882700), F(-6663147, 3220675),
                F(270954, 644135), F(-108, 5875), F(114, 1645)]
    a[7][:7] = [F(13836959, 3667458), F(-17731450, 1833729), F(1063919505, 156478208),
                F(-33213845, 39119552), F(13335, 28544), F(-705, 14272), F(1645, 57088)]
    b_bar = [F(223, 7938), F(0), F(1175, 8064), F(925, 6048), F(41, 448), F(925, 14112),
             F(1175, 72576), F(0), F(0)]
    a[8] = list(b_bar)  # first same as last: the ninth stage is the new position
    b = [F(223, 7938), F(0), F(5875, 36288), F(4625, 21168), F(41, 224), F(4625, 21168),
         F(5875, 36288), F(223, 7938), F(0)]
    e_bar = [F(7987313, 109941300), F(0), F(1610737, 44674560), F(10023263, 33505920),
             F(-497221, 12409600), F(10023263, 78180480), F(1610737, 402071040), F(0), F(0)]
    e = [F(7987313, 109941300), F(0), F(1610737, 40207104), F(10023263, 23454144),
         F(-497221, 6204800), F(10023263, 23454144), F(1610737, 40207104),
         F(-4251941, 54970650), F(3, 20)]
    results = [check("rkn8 main", c, a, b_bar, b, 8), check("rkn8 embedded", c, a, e_bar, e, 6)]
    sys.exit(0 if all(results) else 1)
