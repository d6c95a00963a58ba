#!/usr/bin/env python3
# Exact rational values of the two hard cases in tests/analysis/stats/test_edge_cases.cpp
# (Python's fractions module, no floating point): Mauchly's W of nearly collinear contrasts,
# and the tiny real residual beside effects of size 2.5e14. Prints each value as a fraction
# and as the nearest double. Run: python3 tests/analysis/data/stats_exact_hard_cases.py
from fractions import Fraction as Fr


def sphericity(Y):
    """E in the orthonormal Helmert basis of 3 levels; returns tr E, GG, HF, Mauchly W (= p here)."""
    n = len(Y)
    a = [Fr(r[0] - r[1]) for r in Y]
    b = [Fr(r[0] + r[1] - 2 * r[2]) for r in Y]
    ma, mb = sum(a) / n, sum(b) / n
    a = [x - ma for x in a]
    b = [x - mb for x in b]
    saa, sbb = sum(x * x for x in a), sum(x * x for x in b)
    sab = sum(x * y for x, y in zip(a, b))
    e11, e22, e12sq = saa / 2, sbb / 6, sab * sab / 12  # contrasts (1,-1,0)/sqrt2, (1,1,-2)/sqrt6
    tr, tr2 = e11 + e22, e11 * e11 + e22 * e22 + 2 * e12sq
    p, dfe = 2, n - 1
    gg = tr * tr / (p * tr2)
    hf = ((dfe + 1) * p * gg - 2) / (p * (dfe - p * gg))
    w = (e11 * e22 - e12sq) / (tr / 2) ** 2
    return tr, gg, hf, w


def anova(Y):
    """One within factor: SS_cond, SS_error, F."""
    N, k = len(Y), len(Y[0])
    rows = [Fr(sum(r), k) for r in Y]
    cols = [Fr(sum(Y[i][j] for i in range(N)), N) for j in range(k)]
    g = Fr(sum(map(sum, Y)), N * k)
    ss_cond = N * sum((c - g) ** 2 for c in cols)
    ss_err = sum((Y[i][j] - rows[i] - cols[j] + g) ** 2 for i in range(N) for j in range(k))
    return ss_cond, ss_err, (ss_cond / (k - 1)) / (ss_err / ((N - 1) * (k - 1)))


collinear = [[9999999, 20000001, 2], [20000001, 39999997, 4], [29999998, 60000001, 7], [50000002, 99999997, 3]]
tiny = [[-2, 125000000000003, 250000000000003], [12, 125000000000008, 250000000000013],
        [17, 125000000000017, 250000000000020], [28, 125000000000032, 250000000000031]]
for name, Y in (("nearly collinear", collinear), ("tiny residual", tiny)):
    tr, gg, hf, w = sphericity(Y)
    ss, sse, f = anova(Y)
    for label, v in (("SS_cond", ss), ("SS_error", sse), ("F", f), ("GG", gg), ("HF", hf), ("Mauchly W = p", w)):
        print(f"{name}: {label} = {v} = {float(v)!r}")
