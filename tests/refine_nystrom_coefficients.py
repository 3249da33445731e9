#!/usr/bin/env python3
"""Refines the published coefficients of the Runge-Kutta-Nystrom splitting
tables (src/scheme/nystrom_splitting.rs) to full double precision by Newton
iteration on their order conditions for q'' = a(q).

Why not the matrix test of refine_coefficients.py. A splitting method for
q'' = a(q) alternates the drift exp(hA) (q += c h v) and the kick exp(hB)
(v += c h a(q)). Because the kick's vector field depends on q only and the
drift's is linear in v, [B, [B, [B, A]]] = 0 for every force (Hairer, Lubich,
Wanner, Geometric Numerical Integration, 2006, III.3.2 and V.3.3): the
Nystrom methods are built to satisfy only the order conditions that survive
this relation, and generic matrices A, B would reject them. So the
conditions are taken from a nonlinear q'' = a(q) itself.

Method. One step of the method applied to power series in h: the initial
point (q0, v0) is a constant series, a drift adds c h v, a kick c h a(q) with
the force evaluated on series (truncated products). The exact flow's Taylor
series comes from q(t) = sum Q_k t^k, Q_(k+2) = [a(q(t))]_k / ((k+1)(k+2)).
The coefficients of h^1 .. h^p of method minus exact flow vanish for every
force and initial point exactly when the method has order p for q'' = a(q)
(they are the sums over Nystrom trees of the condition defects times the
elementary differentials). The force is a polynomial in D = 2 unknowns with
pseudo-random rational coefficients and every monomial up to degree 7, so
each elementary differential up to h^9 is present (it involves derivatives
of a of order at most 7), and four initial points make the residual vanish
only when every condition holds. The Jacobian's rank, printed, is the number
of independent conditions the test sees; it matches the count of Nystrom
conditions not already met by consistency and symmetry: 2 for symmetric
order 4 (those of h^3), 7 for the non-symmetric order 4; on the sixth-order
Runge-Kutta-Nystrom splittings of Blanes & Moan (2002) it is 6 (2 of h^3, 4
of h^5 out of the 6 of a generic splitting).

Layout. Which weights are the kicks and which flow comes first is not
always explicit in print; the layout given below for each table is the one
with the claimed order and the small error: exchanging kicks and drifts
costs McLachlan-Atela an order (tests/harness/nystrom_conditions.rs checks
that), and multiplies the h^5 defect of SB3A, which stays of order 4 either
way, by 2.8.

Gauss-Newton with the pseudo-inverse of the Jacobian (central differences),
minimum-norm steps: a family with free parameters (every table here has some,
used by its authors to minimise the error terms) is refined to its member
nearest to the published digits. mpmath at 60 digits throughout. The script
prints the residuals before and after, the distance from the published
digits, and each coefficient rounded to the nearest double, which is what
src/scheme/nystrom_splitting.rs stores.

Run: python3 tests/refine_nystrom_coefficients.py   (needs mpmath; a few minutes)
"""

from mpmath import mp, mpf

mp.dps = 60
D = 2
DEGREE = 7  # of the force polynomial
POINTS = 4

_lcg = [12345]


def rand():
    """A deterministic rational in [-1, 1] with step 1/1000."""
    _lcg[0] = (6364136223846793005 * _lcg[0] + 1442695040888963407) % 2**64
    return mpf((_lcg[0] >> 33) % 2001 - 1000) / 1000


MONOMIALS = [(i, j) for i in range(DEGREE + 1) for j in range(DEGREE + 1 - i)]
# coefficients shrink with the degree so the series converge for |h| ~ 1
FORCE = [{m: rand() / (1 + m[0] + m[1]) ** 2 for m in MONOMIALS} for _ in range(D)]
STARTS = [([rand() / 2 for _ in range(D)], [rand() / 2 for _ in range(D)]) for _ in range(POINTS)]


def mul(x, y, n):
    return [sum((x[i] * y[k - i] for i in range(k + 1)), mpf(0)) for k in range(n)]


def force(q, n):
    """a(q) on series q (one per coordinate), truncated to n terms."""
    powers = []
    for c in range(D):
        p = [[mpf(1)] + [mpf(0)] * (n - 1)]
        for _ in range(DEGREE):
            p.append(mul(p[-1], q[c], n))
        powers.append(p)
    out = []
    for comp in FORCE:
        acc = [mpf(0)] * n
        for (i, j), coef in comp.items():
            term = mul(powers[0][i], powers[1][j], n)
            for k in range(n):
                acc[k] += coef * term[k]
        out.append(acc)
    return out


def exact(q0, v0, n):
    """Taylor coefficients of q(h) and v(h), n terms each."""
    q = [[q0[c], v0[c]] + [mpf(0)] * (n - 1) for c in range(D)]
    for k in range(n - 1):
        a = force([s[:k + 1] + [mpf(0)] * (n - k) for s in q], n + 1)
        for c in range(D):
            q[c][k + 2] = a[c][k] / ((k + 1) * (k + 2))
    v = [[(k + 1) * q[c][k + 1] for k in range(n)] for c in range(D)]
    return [s[:n] for s in q], v


def method(sequence, q0, v0, n):
    q = [[q0[c]] + [mpf(0)] * (n - 1) for c in range(D)]
    v = [[v0[c]] + [mpf(0)] * (n - 1) for c in range(D)]
    for flow, w in sequence:
        if flow == "D":
            for c in range(D):
                for k in range(n - 1, 0, -1):
                    q[c][k] += w * v[c][k - 1]
        else:
            a = force(q, n)
            for c in range(D):
                for k in range(n - 1, 0, -1):
                    v[c][k] += w * a[c][k - 1]
    return q, v


EXACT = {}
SELECTED = []


def defects(sequence, degree):
    """Per power h^0..h^degree, the list of q and v defects over all points."""
    n = degree + 1
    out = [[] for _ in range(n)]
    for idx, (q0, v0) in enumerate(STARTS):
        if (idx, n) not in EXACT:
            EXACT[(idx, n)] = exact(q0, v0, n)
        qe, ve = EXACT[(idx, n)]
        qm, vm = method(sequence, q0, v0, n)
        for k in range(n):
            for c in range(D):
                out[k] += [qm[c][k] - qe[c][k], vm[c][k] - ve[c][k]]
    return out


def to_f64(v):
    """The double nearest to v (through a 40-digit decimal: correctly rounded)."""
    return float(mp.nstr(v, 40, min_fixed=-1, max_fixed=1))


def size(ds, k):
    return max(abs(e) for e in ds[k])


def refine(name, build, start, order):
    x = [mpf(v) for v in start]
    if SELECTED and name not in SELECTED:
        return x
    r0 = defects(build(x), order + 1)
    print(f"\n== {name} (order {order})")
    print("  published: max |h^k defect| per k = 1..p+1:",
          " ".join(f"{float(size(r0, k)):.1e}" for k in range(1, order + 2)))

    def flat(y):
        ds = defects(build(y), order)
        return [e for k in range(1, order + 1) for e in ds[k]]

    for it in range(12):
        r = flat(x)
        norm = max(abs(e) for e in r)
        if norm < mpf(10) ** (-mp.dps + 8):
            break
        cols = []
        eps = mpf(10) ** (-25)
        for i in range(len(x)):
            xp, xm = list(x), list(x)
            xp[i] += eps
            xm[i] -= eps
            cols.append([(a - b) / (2 * eps) for a, b in zip(flat(xp), flat(xm))])
        J = mp.matrix(len(r), len(cols))
        for j, col in enumerate(cols):
            for i, v in enumerate(col):
                J[i, j] = v
        U, S, V = mp.svd_r(J)
        rank = sum(1 for s in S if s > S[0] * mpf(10) ** -30)
        step = [mpf(0)] * len(x)
        for k in range(rank):
            coef = mp.fsum(U[i, k] * r[i] for i in range(len(r))) / S[k]
            for j in range(len(x)):
                step[j] += coef * V[k, j]
        x = [a - b for a, b in zip(x, step)]
        print(f"  iteration {it}: residual {float(norm):.1e}, rank {rank} of {len(x)}")
    r1 = defects(build(x), order + 1)
    print("  refined:   max |h^k defect| per k = 1..p+1:",
          " ".join(f"{float(size(r1, k)):.1e}" for k in range(1, order + 2)))
    print("  published - refined:", " ".join(f"{float(mpf(a) - b):.1e}" for a, b in zip(start, x)))
    for v in x:
        print(f"  {mp.nstr(v, 30):>36}  -> f64 {to_f64(v)!r}")
    return x


def alternating(first, lead, lag):
    """`first` with lead[0], the other flow with lag[0], and so on."""
    other = "D" if first == "K" else "K"
    seq = []
    for i, w in enumerate(lead):
        seq.append((first, mpf(w)))
        if i < len(lag):
            seq.append((other, mpf(lag[i])))
    return seq


def show(name, v):
    print(f"  {name} {mp.nstr(v, 30)} -> f64 {to_f64(v)!r}")


if __name__ == "__main__":
    import sys

    SELECTED = sys.argv[1:]  # table names; all when none given
    # McLachlan & Atela (1992), Table 2, optimal fourth order for quadratic
    # kinetic energy: b1 a1 b2 a2 b3 a3 b4 a4, kick first (the other
    # assignments are of order 3 at most). All eight weights are unknowns.
    x = refine("mclachlan-atela4", lambda x: alternating("K", x[:4], x[4:]),
               ["0.1344961992774310892", "-0.2248198030794208058", "0.7563200005156682911",
                "0.3340036032863214255",
                "0.5153528374311229364", "-0.085782019412973646", "0.4415830236164665242",
                "0.1288461583653841854"], 4)

    # McLachlan (1995), SB3A with four evaluations: drift first,
    # a1 b1 a2 b2 a3 b2 a2 b1 a1 with a3 = 1 - 2 (a1 + a2), b2 = 1/2 - b1.
    # Unknowns a1 a2 b1.
    def sb3a4(x):
        a = [x[0], x[1], 1 - 2 * (x[0] + x[1]), x[1], x[0]]
        b = [x[2], mpf(1) / 2 - x[2]]
        return alternating("D", a, b + list(reversed(b)))
    x = refine("mclachlan-sb3a4", sb3a4,
               ["0.18819521776883821787", "-0.021528551102171551201", "1"], 4)
    show("a3", 1 - 2 * (x[0] + x[1]))
    show("b2", mpf(1) / 2 - x[2])

    # McLachlan (1995), SB3A with five evaluations: drift first,
    # a1 b1 a2 b2 a3 b3 a3 b2 a2 b1 a1 with a3 = 1/2 - (a1 + a2),
    # b3 = 1 - 2 (b1 + b2). Unknowns a1 a2 b1 b2.
    def sb3a5(x):
        a = [x[0], x[1], mpf(1) / 2 - x[0] - x[1]]
        b = [x[2], x[3], 1 - 2 * (x[2] + x[3]), x[3], x[2]]
        return alternating("D", a + list(reversed(a)), b)
    x = refine("mclachlan-sb3a5", sb3a5,
               ["0.4051886183952522772", "-0.2871440408165240890",
                "-0.041095890410958904110", "0.28813559322033898305"], 4)
    show("a3", mpf(1) / 2 - x[0] - x[1])
    show("b3", 1 - 2 * (x[2] + x[3]))

    # Blanes & Moan (2002), Table 3, SRKN_11^b, order 6: kick first,
    # b1 a1 ... b6 a6 b6 a5 ... a1 b1 with b6 = 1/2 - (b1 + ... + b5),
    # a6 = 1 - 2 (a1 + ... + a5). Unknowns b1..b5, a1..a5.
    def srkn11b(x):
        b = x[:5] + [mpf(1) / 2 - mp.fsum(x[:5])]
        a = x[5:] + [1 - 2 * mp.fsum(x[5:])]
        return alternating("K", b + list(reversed(b)), a + list(reversed(a[:-1])))
    x = refine("blanes-moan-srkn11b", srkn11b,
               ["0.0414649985182624", "0.198128671918067", "-0.0400061921041533",
                "0.0752539843015807", "-0.0115113874206879",
                "0.123229775946271", "0.290553797799558", "-0.127049212625417",
                "-0.246331761062075", "0.357208872795928"], 6)
    show("b6", mpf(1) / 2 - mp.fsum(x[:5]))
    show("a6", 1 - 2 * mp.fsum(x[5:]))

