#!/usr/bin/env python3
"""Refines the published coefficients of the splitting and composition tables
to full double precision by Newton iteration on their order conditions.

Method. A splitting method applied to the linear problem y' = (A + B) y,
with the drift the flow of A and the kick the flow of B, is the product of
exponentials exp(c_m h X_m) ... exp(c_1 h X_1). It has order p exactly when
the Taylor coefficients of h^1 .. h^p of that product equal those of
exp(h (A + B)) for generic, non-commuting A and B. Here A and B are 5 x 5
matrices with pseudo-random rational entries: by the Amitsur-Levitzki theorem
the n x n matrices satisfy no polynomial identity of degree below 2n = 10, so
no order condition up to degree 9 can vanish by accident of the dimension.

The residual (every entry of the coefficient differences of h^1 .. h^p) is a
polynomial in the free coefficients. Starting from the published digits,
Gauss-Newton steps with the pseudo-inverse of the Jacobian (central
differences) converge to the nearest exact solution; for a family with free
parameters (Kahan and Li's 17 stages have one more than the order conditions
fix, PEFRL has one free parameter too) the minimum-norm step picks the
solution nearest the published point.
All arithmetic is mpmath at 60 decimal digits. The script prints, per table,
the residual at the published digits and after refinement, how far the
published digits were from the refined solution, and each coefficient rounded
to the nearest double, which is what src/scheme/ stores.

Run: python3 tests/refine_coefficients.py   (needs mpmath; about a minute)
"""

from mpmath import mp, mpf, cbrt

mp.dps = 60
N = 5  # matrix size: 2N > 9, the highest degree checked


def random_matrix(seed):
    """A deterministic N x N matrix with entries k/1000, k in [-1000, 1000]."""
    state = seed
    rows = []
    for _ in range(N):
        row = []
        for _ in range(N):
            state = (6364136223846793005 * state + 1442695040888963407) % 2**64
            row.append(mpf((state >> 33) % 2001 - 1000) / 1000)
        rows.append(row)
    return rows


def matmul(x, y):
    return [[mp.fsum(x[i][k] * y[k][j] for k in range(N)) for j in range(N)] for i in range(N)]


def add_scaled(acc, x, c):
    for i in range(N):
        for j in range(N):
            acc[i][j] += c * x[i][j]


def zero():
    return [[mpf(0)] * N for _ in range(N)]


def identity():
    return [[mpf(1 if i == j else 0) for j in range(N)] for i in range(N)]


A, B = random_matrix(1), random_matrix(2)


def powers(x, degree):
    """x^k / k! for k = 0..degree."""
    out = [identity()]
    for k in range(1, degree + 1):
        p = matmul(out[-1], x)
        out.append([[e / k for e in row] for row in p])
    return out


def residual_series(sequence, degree):
    """Coefficients of h^0..h^degree of the method's product minus exp(h(A+B)).

    `sequence` lists (flow, weight) in order of application, flow "D" (A) or
    "K" (B); later flows multiply from the left.
    """
    pa, pb = powers(A, degree), powers(B, degree)
    product = [identity()] + [zero() for _ in range(degree)]
    for flow, c in sequence:
        p = pa if flow == "D" else pb
        new = [zero() for _ in range(degree + 1)]
        for j in range(degree + 1):  # exp(c h X) has c^j X^j / j! at h^j
            cj = c**j
            for k in range(degree + 1 - j):
                add_scaled(new[j + k], matmul(p[j], product[k]), cj)
        product = new
    s = [[A[i][j] + B[i][j] for j in range(N)] for i in range(N)]
    exact = powers(s, degree)
    return [[[product[k][i][j] - exact[k][i][j] for j in range(N)] for i in range(N)]
            for k in range(degree + 1)]


def to_f64(v):
    """The double nearest to v (through a 40-digit decimal: correctly rounded)."""
    return float(mp.nstr(v, 40, min_fixed=-1, max_fixed=1))


def flat(series, lo, hi):
    return [series[k][i][j] for k in range(lo, hi + 1) for i in range(N) for j in range(N)]


def size(series, k):
    return max(abs(e) for row in series[k] for e in row)


def verlet_composition(w):
    """Velocity Verlet (kick w/2, drift w, kick w/2) composed with weights w."""
    seq = [("K", w[0] / 2)]
    for i, wi in enumerate(w):
        seq.append(("D", wi))
        nxt = w[i + 1] if i + 1 < len(w) else 0
        seq.append(("K", (wi + nxt) / 2))
    return seq


def palindrome(outer):
    """w_1 .. w_m, centre, w_m .. w_1 with the centre fixed by sum w = 1."""
    centre = 1 - 2 * mp.fsum(outer)
    return list(outer) + [centre] + list(reversed(outer))


def pefrl(params):
    xi, lam, chi = params
    return [("D", xi), ("K", (1 - 2 * lam) / 2), ("D", chi), ("K", lam),
            ("D", 1 - 2 * (chi + xi)), ("K", lam), ("D", chi),
            ("K", (1 - 2 * lam) / 2), ("D", xi)]


def refine(name, build, start, order):
    """Gauss-Newton on the conditions h^1..h^order from the published `start`."""
    x = [mpf(v) for v in start]
    r0 = residual_series(build(x), order + 1)
    print(f"\n== {name} (order {order})")
    print("  published: max |h^k coefficient| per k = 1..p+1:",
          " ".join(f"{float(size(r0, k)):.1e}" for k in range(1, order + 2)))
    for it in range(12):
        r = flat(residual_series(build(x), order), 1, order)
        norm = max(abs(e) for e in r)
        if norm < mpf(10) ** (-mp.dps + 8):
            break
        cols = []
        eps = mpf(10) ** (-25)
        for i in range(len(x)):
            xp, xm = list(x), list(x)
            xp[i] += eps
            xm[i] -= eps
            rp = flat(residual_series(build(xp), order), 1, order)
            rm = flat(residual_series(build(xm), order), 1, order)
            cols.append([(a - b) / (2 * eps) for a, b in zip(rp, rm)])
        J = mp.matrix(len(r), len(cols))
        for j, col in enumerate(cols):
            for i, v in enumerate(col):
                J[i, j] = v
        U, S, V = mp.svd_r(J)
        rank = sum(1 for s in S if s > S[0] * mpf(10) ** -30)
        rv = mp.matrix(r)
        step = mp.matrix(len(cols), 1)
        for k in range(rank):
            coef = sum(U[i, k] * rv[i] for i in range(len(r))) / S[k]
            for j in range(len(cols)):
                step[j] += coef * V[k, j]
        for i in range(len(x)):
            x[i] -= step[i]
        print(f"  iteration {it}: residual {float(norm):.1e}, rank {rank} of {len(cols)}")
    r1 = residual_series(build(x), order + 1)
    print("  refined:   max |h^k coefficient| per k = 1..p+1:",
          " ".join(f"{float(size(r1, k)):.1e}" for k in range(1, order + 2)))
    print("  published - refined:", " ".join(f"{float(mpf(a) - b):.1e}" for a, b in zip(start, x)))
    for v in x:
        print(f"  {mp.nstr(v, 30):>36}  -> f64 {to_f64(v)!r}")
    return x


if __name__ == "__main__":
    x1 = 1 / (2 - cbrt(2))
    print("Forest-Ruth / Yoshida triple jump: w1 = 1/(2 - 2^(1/3)), w0 = 1 - 2 w1")
    refine("forest-ruth", lambda x: verlet_composition(palindrome(x)), [x1], 4)
    print(f"  centre {mp.nstr(1 - 2 * x1, 30)} -> f64 {to_f64(1 - 2 * x1)!r}")

    # Omelyan, Mryglod & Folk (2002): xi, lambda, chi, a one-parameter family
    # of fourth-order methods; the minimum-norm steps find its member nearest
    # to the published point.
    refine("pefrl", pefrl,
           ["0.1786178958448091", "-0.2123418310626054", "-0.06626458266981849"], 4)

    # Yoshida (1990), Table 1, solution A: w1, w2, w3 (w0 = 1 - 2 sum).
    y6 = refine("yoshida6", lambda x: verlet_composition(palindrome(list(reversed(x)))),
                ["-1.17767998417887", "0.235573213359357", "0.784513610477560"], 6)
    print(f"  w0 {mp.nstr(1 - 2 * mp.fsum(y6), 30)} -> f64 {to_f64(1 - 2 * mp.fsum(y6))!r}")

    # Kahan & Li (1997), s17odr8a, gamma_1 .. gamma_8 (gamma_9 = 1 - 2 sum).
    kl = refine("kahan-li8", lambda x: verlet_composition(palindrome(x)),
                ["0.13020248308889008087881763", "0.56116298177510838456196441",
                 "-0.38947496264484728640807860", "0.15884190655515560089621075",
                 "-0.39590389413323757733623154", "0.18453964097831570709183254",
                 "0.25837438768632204729397911", "0.29501172360931029887096624"], 8)
    g9 = 1 - 2 * mp.fsum(kl)
    print(f"  gamma_9 {mp.nstr(g9, 30)} -> f64 {to_f64(g9)!r}"
          f" (published -0.60550853383003451169892108,"
          f" difference {float(g9 - mpf('-0.60550853383003451169892108')):.1e})")
