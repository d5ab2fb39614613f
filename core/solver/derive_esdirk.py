#!/usr/bin/env python3
"""Derives Asgard's stiff method, a 4-stage ESDIRK of order 3 with an embedded
formula of order 2 (explicit first stage, stiffly accurate, L-stable, stage
order 2), from its defining conditions, and writes its table as C++ for
core/solver/esdirk.h (kEsdirk32 there is this script's output).

Structure: c = (0, 2g, c3, 1), A lower triangular with a_11 = 0 and
a_ii = g (i = 2, 3, 4); row 4 of A is b (stiffly accurate: the last stage is
the solution, so its rate is the new sample's rate and stiff modes are damped
as L-stability promises).

Conditions, each a linear system once g and c3 are fixed:
  * stage order 2 on every row: sum_j a_ij = c_i, sum_j a_ij c_j = c_i^2 / 2
    (row 2 then forces a_21 = g, c_2 = 2g; row 3 gives a_31, a_32);
  * order 3 of b: sum b = 1, sum b c = 1/2, sum b c^2 = 1/3 (the fourth tree,
    sum b A c = 1/6, follows from stage order 2);
  * L-stability: the stability function R(z) = P(z)/(1 - gz)^3 has
    R(inf) = 0 when g is the root of 6g^3 - 18g^2 + 9g - 1 in (0.4, 0.5);
    A-stability is checked on the imaginary axis (the poles 1/g lie in the
    right half plane, so the maximum principle covers the left one).

Our choices:
  * c3 = 3/5: the round value nearest the minimum over c3 of the 2-norm of
    the 4th-order error coefficients (the minimum is printed; it lies near
    0.6, and the norm is flat there).
  * embedded formula b_hat: order 2 (sum = 1, sum c = 1/2) with
    sum b_hat c^2 = 1/3 - delta, and a stability function bounded at
    infinity (the component of z (I - zA)^-1 1 that grows with z must vanish
    in b_hat).  Then R_hat(inf) is proportional to delta; delta = -1/20 keeps
    the embedded formula A-stable, its weights below 0.6 in magnitude, and
    the estimate (delta/2) h^3 y''' of the size of TR-BDF2's error constant,
    so the step controller's calibration carries over.  The estimate is
    filtered through (I - g h J)^-1 in the component (as TR-BDF2's is), so
    stiff modes that have decayed do not hold the step down.
"""
import mpmath as mp

mp.mp.dps = 40


def tableau(g, c3):
    c2 = 2 * g
    a32 = (c3 ** 2 / 2 - g * c3) / c2
    a31 = c3 - g - a32
    sol = mp.lu_solve(mp.matrix([[c2, c3], [c2 ** 2, c3 ** 2]]),
                      mp.matrix([mp.mpf(1) / 2 - g, mp.mpf(1) / 3 - g]))
    b2, b3 = sol[0], sol[1]
    b1 = 1 - g - b2 - b3
    A = [[0, 0, 0, 0], [g, g, 0, 0], [a31, a32, g, 0], [b1, b2, b3, g]]
    return A, [mp.mpf(0), c2, c3, mp.mpf(1)]


def stability(A, b, z):
    M = mp.eye(4) - z * mp.matrix(A)
    x = mp.lu_solve(M, mp.matrix([1] * 4))
    return 1 + z * sum(b[i] * x[i] for i in range(4))


def error4(A, c):
    b = A[3]
    Ac = [mp.fsum(A[i][j] * c[j] for j in range(4)) for i in range(4)]
    Ac2 = [mp.fsum(A[i][j] * c[j] ** 2 for j in range(4)) for i in range(4)]
    AAc = [mp.fsum(A[i][j] * Ac[j] for j in range(4)) for i in range(4)]
    # tau(t) = (Phi(t) - 1/gamma(t)) / sigma(t) for the four trees of order 4
    r = [(mp.fdot(b, [x ** 3 for x in c]) - mp.mpf(1) / 4) / 6,
         mp.fdot(b, [c[i] * Ac[i] for i in range(4)]) - mp.mpf(1) / 8,
         (mp.fdot(b, Ac2) - mp.mpf(1) / 12) / 2,
         mp.fdot(b, AAc) - mp.mpf(1) / 24]
    return mp.sqrt(mp.fsum(x ** 2 for x in r))


def main():
    g = mp.findroot(lambda x: 6 * x ** 3 - 18 * x ** 2 + 9 * x - 1, mp.mpf('0.43'))
    best = mp.findroot(lambda c3: mp.diff(lambda s: error4(*tableau(g, s)), c3), mp.mpf('0.6'))
    c3 = mp.mpf(3) / 5
    A, c = tableau(g, c3)
    b = A[3]
    # order and stage-order residuals
    res = max(abs(mp.fsum(A[i]) - c[i]) for i in range(4))
    res = max(res, max(abs(mp.fdot(A[i], c) - c[i] ** 2 / 2) for i in range(4)))
    res = max(res, abs(mp.fdot(b, [x ** 2 for x in c]) - mp.mpf(1) / 3))
    r_inf = stability(A, b, mp.mpf(-10) ** 15)
    ys = [mp.mpf(10) ** (k / mp.mpf(20)) for k in range(-60, 200)]
    a_stable = max(abs(stability(A, b, mp.mpc(0, y))) for y in ys)
    # embedded formula
    delta = mp.mpf(-1) / 20
    Ai = mp.matrix([[A[i][j] for j in range(1, 4)] for i in range(1, 4)])
    # z (I - zA)^-1 1 -> grows like z in its first component; the part of
    # b_hat that multiplies the growth: with k_1 explicit, stage values
    # x_i = 1 + z a_i1 + ..., the growing term of b_hat^T z x is
    # z (bh_1 + sum_{i>1} bh_i w_i), w = -(A~)^-1 a_.1 ... solved numerically:
    w = mp.lu_solve(Ai, mp.matrix([A[i][0] for i in range(1, 4)]))
    grow = [mp.mpf(1)] + [-w[i] for i in range(3)]
    M = mp.matrix([[1] * 4, c, [x ** 2 for x in c], grow])
    sol = mp.lu_solve(M, mp.matrix([1, mp.mpf(1) / 2, mp.mpf(1) / 3 - delta, 0]))
    bhat = [sol[i] for i in range(4)]
    rh_inf = stability(A, bhat, mp.mpf(-10) ** 15)
    rh_max = max(abs(stability(A, bhat, mp.mpc(0, y))) for y in ys)
    e = [b[i] - bhat[i] for i in range(4)]
    assert res < mp.mpf(10) ** -30 and abs(r_inf) < mp.mpf(10) ** -12 and a_stable <= 1
    assert rh_max <= 1
    f = lambda v: mp.nstr(v, 17, strip_zeros=False) if v != 0 else '0.0'
    print('// gamma = %s; c3 = 3/5 (error-norm minimum at c3 = %s: %s there, %s at 3/5)'
          % (mp.nstr(g, 20), mp.nstr(best, 6), mp.nstr(error4(*tableau(g, best)), 6),
             mp.nstr(error4(A, c), 6)))
    print('// conditions met to %s; R(inf) = %s; max |R(iy)| = %s' %
          (mp.nstr(res, 2), mp.nstr(r_inf, 2), mp.nstr(a_stable, 12)))
    print('// embedded: R_hat(inf) = %s, max |R_hat(iy)| = %s; b_hat = %s' %
          (mp.nstr(rh_inf, 6), mp.nstr(rh_max, 12), ', '.join(mp.nstr(v, 6) for v in bhat)))
    print('inline constexpr Esdirk kEsdirk32 = {')
    print('    %s,' % f(g))
    print('    {' + ', '.join(f(x) for x in c) + '},')
    print('    {{},')
    for i in range(1, 4):
        print('     {' + ', '.join(f(A[i][j]) for j in range(i)) + '},')
    print('    },')
    print('    {' + ', '.join(f(v) for v in e) + '}};')


if __name__ == '__main__':
    main()
