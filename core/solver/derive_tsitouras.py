#!/usr/bin/env python3
"""Derives the coefficients of Tsitouras' 5(4) Runge-Kutta pair (Ch. Tsitouras,
"Runge-Kutta pairs of order 5(4) satisfying only the first column simplifying
assumption", Comput. Math. Appl. 62 (2011) 770-775) from its published free
parameters and the order conditions, and writes them as C++ for
core/solver/explicit_pair.h (its kTsitouras table is this script's output).

Published parameters: c2 = 0.161, c3 = 0.327, c4 = 0.9, c5 = 0.9800255409045097,
c6 = c7 = 1, b2 = 0.01 (row 7 = b: first same as last).  The unknowns are the
other a_ij (a_i1 follows from the row sum c_i) and b_1, b_3..b_6; the equations
are the 17 order conditions of order 5 (rooted trees up to 5 nodes) and the
existence of a 4th-order embedded formula: weights u_1..u_6 with
sum u_i Phi_i(t) = rho(t)/gamma(t) for the 8 trees of up to 4 nodes, which
makes n = (u, -1) a null vector of the order-4 conditions (column 7 of those
conditions is rho/gamma because row 7 is b), so b_hat = b - mu n is 4th order
for any mu.  Solved by Gauss-Newton in 40-digit arithmetic from a start near
the solution (found by Levenberg-Marquardt from random starts).

Our own choices (not from the paper):
  * mu: the embedded formula's 5th-order error coefficients get the same
    2-norm as Dormand-Prince's embedded formula, so the error estimate keeps
    the calibration the step controller and the tolerance tests were tuned to.
  * dense output: x(theta) = Hermite cubic + theta^2 (1-theta)^2 h sum d_i k_i
    (the waveform's bubble form).  Order 4 needs sum d_i Phi_i(t) = 0 for trees
    of up to 3 nodes and 1/gamma(t) for those of 4; that system has rank 6, so
    d is free along n; we take the d whose 5th-order error, integrated over
    theta in [0, 1], is least.
"""
import itertools
import mpmath as mp

mp.mp.dps = 40


def trees(n):
    if n == 1:
        return [()]
    res = set()

    def parts(m, maxs):
        if m == 0:
            yield []
            return
        for s in range(min(m, maxs), 0, -1):
            for rest in parts(m - s, s):
                yield [s] + rest

    for p in parts(n - 1, n - 1):
        for combo in itertools.product(*[trees(s) for s in p]):
            res.add(tuple(sorted(combo)))
    return sorted(res)


def order(t):
    return 1 + sum(order(c) for c in t)


def gamma(t):
    g = order(t)
    for c in t:
        g *= gamma(c)
    return g


def phi(A, t):
    s = len(A)
    v = [mp.mpf(1)] * s
    for ch in t:
        w = phi(A, ch)
        for i in range(s):
            v[i] *= sum(A[i][j] * w[j] for j in range(s))
    return v


T = {p: trees(p) for p in range(1, 7)}
UPTO4 = [t for p in range(1, 5) for t in T[p]]
UPTO5 = [t for p in range(1, 6) for t in T[p]]
C = [mp.mpf(0), mp.mpf('0.161'), mp.mpf('0.327'), mp.mpf('0.9'), mp.mpf('0.9800255409045097'),
     mp.mpf(1), mp.mpf(1)]
B2 = mp.mpf('0.01')
FREE = [(i, j) for i in range(2, 6) for j in range(1, i)]  # a_ij, j >= 2 (1-based)


def unpack(x):
    A = [[mp.mpf(0)] * 7 for _ in range(7)]
    for k, (i, j) in enumerate(FREE):
        A[i][j] = x[k]
    for i in range(1, 6):
        A[i][0] = C[i] - sum(A[i][1:i])
    b = [x[10], B2, x[11], x[12], x[13], x[14], mp.mpf(0)]
    A[6] = b[:]
    return A, b, list(x[15:21]) + [mp.mpf(0)]


def residual(x):
    A, b, u = unpack(x)
    r = []
    for t in UPTO5:
        r.append(mp.fdot(b, phi(A, t)) - mp.mpf(1) / gamma(t))
    for t in UPTO4:
        r.append(mp.fdot(u, phi(A, t)) - mp.mpf(order(t)) / gamma(t))
    return r


# Start near the solution (Levenberg-Marquardt from random starts, double precision).
START = [0.33548065540534755, -6.359448473556725, 4.3622954252785044, -11.748883528111822,
         7.495539325600832, -0.09249506620503138, -12.920969276637813, 8.159367878585378,
         -0.07158497306536181, -0.02826905038861683, 0.0964607668153982, 0.47988965042249737,
         1.3790085739805396, -3.290069514953661, 2.324710523735227, 0.11748073091824797,
         0.05388466956918379, -0.5201379442155999, 9.550926457655013, -38.43557286455594,
         30.23341895062909]


def solve():
    x = [mp.mpf(v) for v in START]
    for _ in range(30):
        r = residual(x)
        if max(abs(v) for v in r) < mp.mpf(10) ** -36:
            break
        h = mp.mpf(10) ** -20
        J = mp.matrix(len(r), len(x))
        for k in range(len(x)):
            xp = x[:]
            xp[k] += h
            rp = residual(xp)
            for i in range(len(r)):
                J[i, k] = (rp[i] - r[i]) / h
        dx = mp.lu_solve(J.T * J, -(J.T * mp.matrix(r)))
        x = [a + dx[k] for k, a in enumerate(x)]
    return x


def error_norm(A, w, p):
    return mp.sqrt(sum((mp.fdot(w, phi(A, t)) - mp.mpf(1) / gamma(t)) ** 2 for t in T[p]))


def main():
    x = solve()
    A, b, u = unpack(x)
    res = max(abs(v) for v in residual(x))
    n = u[:6] + [mp.mpf(-1)]
    # Dormand-Prince's embedded formula, for the calibration of mu.
    dp = [[0] * 7 for _ in range(7)]
    dp[1][0] = mp.mpf(1) / 5
    dp[2][:2] = [mp.mpf(3) / 40, mp.mpf(9) / 40]
    dp[3][:3] = [mp.mpf(44) / 45, mp.mpf(-56) / 15, mp.mpf(32) / 9]
    dp[4][:4] = [mp.mpf(19372) / 6561, mp.mpf(-25360) / 2187, mp.mpf(64448) / 6561, mp.mpf(-212) / 729]
    dp[5][:5] = [mp.mpf(9017) / 3168, mp.mpf(-355) / 33, mp.mpf(46732) / 5247, mp.mpf(49) / 176,
                 mp.mpf(-5103) / 18656]
    dp[6][:6] = [mp.mpf(35) / 384, 0, mp.mpf(500) / 1113, mp.mpf(125) / 192, mp.mpf(-2187) / 6784,
                 mp.mpf(11) / 84]
    dp = [[mp.mpf(v) for v in row] for row in dp]
    dp_hat = [mp.mpf(5179) / 57600, 0, mp.mpf(7571) / 16695, mp.mpf(393) / 640,
              mp.mpf(-92097) / 339200, mp.mpf(187) / 2100, mp.mpf(1) / 40]
    target = error_norm(dp, dp_hat, 5)
    # b_hat = b - mu n: its order-5 error is -mu * (sum n_i Phi_i(t)) (b is exact there).
    unit = mp.sqrt(sum(mp.fdot(n, phi(A, t)) ** 2 for t in T[5]))
    mu = target / unit
    bhat = [bi - mu * ni for bi, ni in zip(b, n)]
    e = [bi - bh for bi, bh in zip(b, bhat)]  # error estimate weights: 5th - 4th
    # Dense output: particular d plus nu * n, nu minimizing the integrated 5th-order error.
    rows = UPTO4
    M = [phi(A, t) for t in rows]
    rhs = [mp.mpf(0) if order(t) < 4 else mp.mpf(1) / gamma(t) for t in rows]
    # Particular solution with d_7 = 0 (least squares, exact when consistent).
    Mm = mp.matrix([m[:6] for m in M])
    d6 = mp.lu_solve(Mm.T * Mm, Mm.T * mp.matrix(rhs))
    d0 = [d6[i] for i in range(6)] + [mp.mpf(0)]
    consist = max(abs(mp.fdot(d0, m) - r) for m, r in zip(M, rhs))

    def dense_err(nu):
        d = [a + nu * c for a, c in zip(d0, n)]
        tot = mp.mpf(0)
        for t in T[5]:
            s = mp.fdot(d, phi(A, t))
            # theta^2(1-theta)^2 s + H[theta^5]/gamma - theta^5/gamma, H the cubic Hermite
            # interpolant of theta^5 (values 0, 1; slopes 0, 5 at 0, 1).
            g = gamma(t)
            f = lambda th: (th ** 2 * (1 - th) ** 2 * s +
                            ((3 * th ** 2 - 2 * th ** 3) + 5 * (th ** 3 - th ** 2) - th ** 5) / g) ** 2
            tot += mp.quad(f, [0, 1])
        return tot

    # dense_err is quadratic in nu: three samples give its minimum.
    e0, e1, e2 = dense_err(-1), dense_err(0), dense_err(1)
    nu = (e0 - e2) / (2 * (e0 - 2 * e1 + e2))
    d = [a + nu * c for a, c in zip(d0, n)]
    assert res < mp.mpf(10) ** -20 and consist < mp.mpf(10) ** -20
    assert abs(sum(A[4]) - C[4]) < mp.mpf(10) ** -20
    f = lambda v: mp.nstr(v, 17, strip_zeros=False) if v != 0 else '0.0'
    print('// order conditions met to %s in 40-digit arithmetic' % mp.nstr(res, 2))
    print('constexpr ExplicitPair kTsitouras = {')
    print('    {' + ', '.join(f(C[i]) for i in range(7)) + '},')
    print('    {{},')
    for i in range(1, 7):
        print('     {' + ', '.join(f(A[i][j]) for j in range(i)) + '},')
    print('    },')
    print('    {' + ', '.join(f(v) for v in e) + '},')
    print('    {' + ', '.join(f(v) for v in d) + '}};')


main()
