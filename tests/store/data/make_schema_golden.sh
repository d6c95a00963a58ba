#!/usr/bin/env bash
# Writes the schema goldens of tests/store/test_schema.cpp from databases that an
# earlier build of dtlab created (the build before the schema was generated from
# one description, commit a7efacc): `make_schema_golden.sh FILE.sqlite PGHOST SCHEMA`.
# schema_sqlite.sql: every schema object's SQL text but the trial_table view (which
# depends on the study's factors), in creation order. schema_pg.txt: the PostgreSQL
# catalogue as the queries of schema_pg.sql read it, rows as "a | b | c".
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
sqlite3 "$1" "SELECT sql || ';' FROM sqlite_schema WHERE sql IS NOT NULL AND name <> 'trial_table' ORDER BY rowid" \
  >"$here/schema_sqlite.sql"
PGOPTIONS="-c search_path=$3" psql -X -q -At -F ' | ' -h "$2" -U dtlab -d dtlab_test -f "$here/schema_pg.sql" \
  >"$here/schema_pg.txt"
