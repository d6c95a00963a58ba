#!/usr/bin/env python3
"""Reshapes OBrienKaiser.csv (carData::OBrienKaiser, one row per subject) into
obk_long.csv, the long format of afex::obk.long: id, treatment, gender,
phase (pre, post, fup), hour (1-5), value. Values are copied as text."""
import csv
rows = list(csv.DictReader(open("OBrienKaiser.csv")))
with open("obk_long.csv", "w") as f:
    f.write("id,treatment,gender,phase,hour,value\n")
    for r in rows:
        for phase in ("pre", "post", "fup"):
            for hour in range(1, 6):
                f.write(f"{r['rownames']},{r['treatment']},{r['gender']},{phase},{hour},{r[f'{phase}.{hour}']}\n")
