// Tail probabilities for the tests (F, chi-square, normal, Student t), from
// Boost.Math through complements (cdf(complement(d, x)), never 1 - cdf).
// Guarantees: p is never rounded to 0 while the true tail is above the
// smallest subnormal double (4.9e-324): below 1e-290 p is recomputed from an
// analytic log of the tail; log10_p stays finite and accurate (about 12
// significant digits) far below that, until the statistic itself is infinite.
// Degenerate inputs never throw: NaN statistic or df <= 0 gives p = NaN; an
// infinite statistic gives p = 0, log10_p = -inf; a statistic at or below the
// lower end of the support gives p = 1, log10_p = 0.
// Log-tail formulas (used below 1e-290):
//   F and t: I_x(a, b) = x^a (1-x)^b / (a B(a,b)) * CF, the incomplete-beta
//            continued fraction (Numerical Recipes 3rd ed., 6.4) for x < (a+1)/(a+b+2);
//   chi-square and normal: Q(a, y) = e^-y y^a / Gamma(a) * CF, Legendre's
//            continued fraction for the upper incomplete gamma (NR 6.2), y > a+1;
//            the normal tail as P(|Z| >= z) = Q(1/2, z^2/2).
// Validated against closed forms (F with df1 = 2, chi-square with df = 2,
// t with df = 1 and 2) and mpmath 1.3.0 values written in the tests.
#pragma once

namespace dtlab::stats {

struct Tail {
  double p;        // the tail probability (NaN where undefined)
  double log10_p;  // log10(p), finite where p underflows
};

Tail f_upper(double f, double df1, double df2);  // P(F(df1, df2) >= f); df may be fractional (GG/HF)
Tail chi_squared_upper(double x, double df);     // P(X^2(df) >= x)
Tail normal_upper(double z);                     // P(Z >= z)
Tail normal_lower(double z);                     // P(Z <= z)
Tail normal_two_sided(double z);                 // P(|Z| >= |z|) = 2 min(upper, lower), at most 1
Tail t_upper(double t, double df);               // P(T(df) >= t)
Tail t_lower(double t, double df);               // P(T(df) <= t)
Tail t_two_sided(double t, double df);           // P(|T(df)| >= |t|)

double t_quantile(double prob, double df);       // q with P(T(df) <= q) = prob; NaN for df <= 0
double normal_quantile(double prob);             // q with P(Z <= q) = prob

}  // namespace dtlab::stats
