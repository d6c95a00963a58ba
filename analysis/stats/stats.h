// The statistics library in one include, for callers such as the study
// report (`dtlab analyze`). Typical use: fill a LongData from vectors
//   LongData d; d.subject = ids; d.within = {{"condition", levels}};
//   d.dv = Measurements::from_doubles(times);
// then call rm_anova(d), friedman(d), paired_tests(d), pairwise_within(d, ...)
// and describe(...). Inputs are plain values, results are plain structs;
// problems in the data come back as Error values, degenerate-but-valid data
// as NaN fields plus warnings. Nothing here does I/O except read_csv_file.
#pragma once

#include "analysis/stats/anova.h"          // one_way_anova, Effect
#include "analysis/stats/apa.h"            // apa_p, apa_effect, ...: APA text (rounding for text only)
#include "analysis/stats/assumptions.h"    // shapiro_wilk, anova_residuals
#include "analysis/stats/csv.h"            // read_csv_file, parse_csv, quote_text
#include "analysis/stats/descriptives.h"   // describe
#include "analysis/stats/distributions.h"  // f_upper, chi_squared_upper, normal_*, t_*
#include "analysis/stats/effect_size.h"    // eta_p2_interval, complete_effect
#include "analysis/stats/followup.h"       // simple_effects, within_subject_intervals
#include "analysis/stats/friedman.h"       // friedman, friedman_blocks, ExactOptions
#include "analysis/stats/json.h"           // effect_json, descriptives_json, ...: the one JSON of every result
#include "analysis/stats/long_data.h"      // LongData, long_data_from_csv, long_data_from_wide_csv
#include "analysis/stats/measurements.h"   // Measurements, parse_decimal
#include "analysis/stats/paired.h"         // wilcoxon_signed_rank, sign_test, paired_t, paired_tests
#include "analysis/stats/posthoc.h"        // holm, pairwise_within, pairwise_between
#include "analysis/stats/power.h"          // power_paired_t, power_rm_within, power_of_effect, power_by_resampling
#include "analysis/stats/rm_anova.h"       // rm_anova
#include "analysis/stats/select.h"         // select_rows, parse_row_condition
