// APA-style text of results; see apa.h.
#include "analysis/stats/apa.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dtlab::stats {
namespace {

// v with `decimals` decimals; "-0.00" becomes "0.00".
std::string fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  std::string s = b;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

}  // namespace

Correction applied_correction(const Effect& e, Correction c) {
  if (!e.within || e.df1 <= 1 || std::isnan(e.gg_epsilon) || e.gg_epsilon >= 1.0) return Correction::none;
  if (c == Correction::automatic) return e.mauchly_p < 0.05 ? Correction::greenhouse_geisser : Correction::none;
  if (c == Correction::huynh_feldt && (std::isnan(e.hf_epsilon) || e.hf_epsilon >= 1.0)) return Correction::none;
  return c;
}

std::string apa_p_value(double p) {
  if (std::isnan(p)) return "= NA";
  if (p < 0.001) return "< .001";
  if (p > 0.999) return "> .999";
  return "= " + apa_bounded(p, 3);
}

std::string apa_p(double p) { return "p " + apa_p_value(p); }

std::string apa_bounded(double v, int decimals) {
  if (std::isnan(v)) return "NA";
  std::string s = fixed(v, decimals);
  if (s.rfind("0.", 0) == 0) s.erase(0, 1);
  else if (s.rfind("-0.", 0) == 0) s.erase(1, 1);
  return s;
}

std::string apa_number(double v, int decimals) {
  if (std::isnan(v)) return "NA";
  if (std::isinf(v)) return v > 0 ? "∞" : "-∞";
  if (std::fabs(v) >= 1e6) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*e", decimals, v);
    return b;
  }
  return fixed(v, decimals);
}

std::string apa_df(double df) {
  if (std::isnan(df)) return "NA";
  if (df == std::floor(df) && df < 1e15) return fixed(df, 0);
  return fixed(df, 2);
}

std::string apa_interval(double low, double high, bool bounded, int decimals) {
  auto f = [&](double v) { return bounded ? apa_bounded(v, decimals) : apa_number(v, decimals); };
  return "[" + f(low) + ", " + f(high) + "]";
}

std::string apa_effect(const Effect& e, Correction correction) {
  const Correction c = applied_correction(e, correction);
  double df1 = e.df1, df2 = e.df2, p = e.p, eps = 1.0;
  if (c == Correction::greenhouse_geisser) {
    df1 = e.df1_gg, df2 = e.df2_gg, p = e.p_gg, eps = e.gg_epsilon;
  } else if (c == Correction::huynh_feldt) {
    df1 = e.df1_hf, df2 = e.df2_hf, p = e.p_hf, eps = std::min(1.0, e.hf_epsilon);
  }
  std::string s = "F(" + apa_df(df1) + ", " + apa_df(df2) + ") = " + apa_number(e.F) + ", " + apa_p(p);
  if (c != Correction::none) s += ", ε = " + apa_bounded(eps);
  s += ", ηp² = " + apa_bounded(e.eta_p2);
  if (!std::isnan(e.eta_p2_ci_low)) s += ", 90% CI " + apa_interval(e.eta_p2_ci_low, e.eta_p2_ci_high, true);
  return s;
}

std::string apa_paired_t(const PairedTResult& t) {
  return "t(" + apa_df(t.df) + ") = " + apa_number(t.t) + ", " + apa_p(t.p) + ", d_z = " + apa_number(t.dz) +
         ", M_diff = " + apa_number(t.mean_difference) + ", 95% CI " + apa_interval(t.ci_low, t.ci_high, false);
}

std::string apa_wilcoxon(const WilcoxonResult& w) {
  std::string s = "V = " + apa_number(w.V, w.V == std::floor(w.V) ? 0 : 1);
  if (w.method == "normal") s += ", z = " + apa_number(w.z);
  return s + ", " + apa_p(w.p);
}

}  // namespace dtlab::stats
