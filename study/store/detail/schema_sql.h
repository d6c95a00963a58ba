// The SQL text of the schema migrations and the CHECK-clause builders they
// share (SQLite: schema.cpp v1, schema_v2.cpp v2, schema_v3.cpp v3,
// schema_v4.cpp v4; PostgreSQL: schema_pg.cpp).
// Internal to study/store: the migrations lists in schema.cpp are the only
// callers. Each function returns DDL only; nothing here runs a statement.
#pragma once
#include <string>
#include <string_view>

namespace dtlab::store::detail {

std::string iso_check(std::string_view column);           // CHECK (column GLOB <ISO-8601 UTC ms>)
std::string iso_check_nullable(std::string_view column);  // the same, NULL allowed
std::string hex_check(std::string_view column, int length);  // lowercase hex of exactly `length` digits

std::string schema_v2();  // design hashes, exclusions, notes, pauses, trial attempts, session claims
std::string schema_v3();  // warm-up and late frames per trial, the display of each session start
std::string schema_v4();  // consent answers, withdrawals, the screen log

// PostgreSQL: the header and migrations tables (what SQLite keeps in its file header and
// schema_migrations) and the trigger function that refuses changes; then v1 to v4.
std::string pg_bookkeeping();
std::string pg_schema_v1();
std::string pg_schema_v2();
std::string pg_schema_v3();
std::string pg_schema_v4();

}  // namespace dtlab::store::detail
