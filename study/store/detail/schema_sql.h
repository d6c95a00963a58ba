// The SQL text of the schema migrations and the CHECK-clause builders they
// share (schema.cpp: v1, schema_v2.cpp: v2). Internal to study/store: the
// migrations list in schema.cpp is the only caller of schema_vN(). Each
// function returns DDL only; nothing here runs a statement.
#pragma once
#include <string>
#include <string_view>

namespace dtlab::store::detail {

std::string iso_check(std::string_view column);           // CHECK (column GLOB <ISO-8601 UTC ms>)
std::string iso_check_nullable(std::string_view column);  // the same, NULL allowed
std::string hex_check(std::string_view column, int length);  // lowercase hex of exactly `length` digits

std::string schema_v2();  // design hashes, exclusions, notes, pauses, trial attempts, session claims
std::string schema_v3();  // warm-up and late frames per trial, the display of each session start

}  // namespace dtlab::store::detail
