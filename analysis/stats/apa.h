// Numbers as a paper prints them (APA 7th edition, section 6.36 and table
// 6.5 conventions): the one place where results are rounded for text. JSON
// and CSV keep the exact doubles (json.h); nothing here feeds a computation.
//   p:  three decimals without a leading zero ("p = .002"); below .001
//       "p < .001"; above .999 "p > .999"; undefined "p = NA".
//   Statistics bounded by 1 (eta squared, epsilon, W) without a leading zero
//   (".57"); others with one ("d_z = 0.85", "F = 20.09"); two decimals.
//   df: integers as integers, corrected df with two decimals ("F(1.03, 5.13)").
//   Infinite statistics print as "∞", undefined ones as "NA"; never "-0.00".
//   An effect sentence: "F(1, 15) = 20.09, p < .001, ηp² = .57, 90% CI [.30,
//   .71]"; with a sphericity correction the corrected df and the epsilon
//   ("F(1.03, 5.13) = 6.14, p = .054, ε = .51, ηp² = .55, 90% CI [.00, .79]").
// Pure functions; UTF-8 text; never locale-dependent.
#pragma once
#include <string>

#include "analysis/stats/anova.h"
#include "analysis/stats/paired.h"

namespace dtlab::stats {

// Which df and p an ANOVA sentence reports for a within effect with more than one df.
enum class Correction {
  none,               // uncorrected
  greenhouse_geisser, // GG always (afex's default for its tables)
  huynh_feldt,        // HF (min(1, epsilon))
  automatic,          // GG when Mauchly's p < .05, else none
};

std::string apa_p(double p);                          // "p = .002", "p < .001", "p > .999", "p = NA"
std::string apa_p_value(double p);                    // the same without "p ": "= .002", "< .001"
std::string apa_bounded(double v, int decimals = 2);  // ".57", "1.00", "−" never; NA for NaN
std::string apa_number(double v, int decimals = 2);   // "20.09", "-1.28", "∞", "NA"
std::string apa_df(double df);                        // "15", "5.13"
std::string apa_interval(double low, double high, bool bounded, int decimals = 2);  // "[.30, .71]"

// The correction `correction` comes to for e: none unless e is a within
// effect with df1 > 1 and a defined epsilon below 1 (HF: min(1, HF) below 1).
Correction applied_correction(const Effect& e, Correction correction);

// The sentence for one ANOVA effect (see above); `correction` applies to
// within effects with df1 > 1 and a defined epsilon.
std::string apa_effect(const Effect& e, Correction correction = Correction::greenhouse_geisser);

// "t(9) = -4.06, p = .003, d_z = -1.28, M_diff = -1.58, 95% CI [-2.46, -0.70]".
std::string apa_paired_t(const PairedTResult& t);

// "V = 40, p = .039" (with "z = 2.10" where p is the normal approximation).
std::string apa_wilcoxon(const WilcoxonResult& w);

}  // namespace dtlab::stats
