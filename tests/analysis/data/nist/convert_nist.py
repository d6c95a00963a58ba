#!/usr/bin/env python3
"""Turns the NIST StRD one-way ANOVA .dat files into the CSV files the tests and
`dtlab stats anova` read, keeping every response exactly as written (the
decimal text is copied, never converted to binary floating point), and writes
certified.csv with the certified values (NIST, 15 significant digits).

Usage: convert_nist.py DIR_WITH_DAT_FILES OUT_DIR
Source of the .dat files: NIST ITL Statistical Reference Datasets, ANOVA
(https://www.itl.nist.gov/div898/strd/anova/anova.html), as vendored in
scipy/scipy scipy/stats/tests/data/nist_anova.
"""
import os
import sys

NAMES = ["SiRstv", "SmLs01", "SmLs02", "SmLs03", "AtmWtAg", "SmLs04", "SmLs05", "SmLs06",
         "SmLs07", "SmLs08", "SmLs09"]


def convert(path):
    lines = open(path).read().splitlines()
    between = within = r2 = sd = None
    data_start = None
    for i, line in enumerate(lines):
        words = line.split()
        if line.startswith("Between"):
            between = words[2:]          # df SS MS F
        elif line.startswith("Within"):
            within = words[2:]           # df SS MS
        elif "Certified R-Squared" in line:
            r2 = words[-1]
        elif "Standard Deviation" in line and sd is None and i < 60:
            sd = words[-1]
        if line.startswith("Data:") and len(words) == 3:
            data_start = i + 1
            columns = words[1:]
    rows = [l.split() for l in lines[data_start:] if l.strip()]
    return columns, rows, between, within, r2, sd


def main():
    src, out = sys.argv[1], sys.argv[2]
    cert = ["dataset,df_between,ss_between,ms_between,F,df_within,ss_within,ms_within,r_squared,residual_sd"]
    for name in NAMES:
        columns, rows, between, within, r2, sd = convert(os.path.join(src, name + ".dat"))
        with open(os.path.join(out, name + ".csv"), "w") as f:
            f.write("treatment,response\n")
            for t, y in rows:
                f.write(f"{t},{y}\n")
        cert.append(",".join([name] + between[:4] + within[:3] + [r2, sd]))
    with open(os.path.join(out, "certified.csv"), "w") as f:
        f.write("\n".join(cert) + "\n")


if __name__ == "__main__":
    main()
