// Where a PostgreSQL study lives, from the URI a user gives: libpq's own
// connection URI (postgresql://user@host:port/database?...) plus dtlab's one
// parameter, `schema` (default `public`): one study per schema, so one
// database can hold several studies. Pure functions; never connects and never
// puts a password into a name that errors or output show.
#pragma once
#include <cstdint>
#include <string>

#include "study/common/error.h"

namespace dtlab::store::detail {

struct PgAddress {
  std::string conninfo;  // the URI for libpq, without dtlab's `schema` parameter
  std::string schema;    // the study's schema: lowercase letters, digits, _; not pg_*
  std::string display;   // the URI without any password, with the schema: what errors and output name
  std::int32_t lock_key = 0;  // second key of the study's advisory lock (the first is kApplicationId)
};

// Splits and checks `uri` (postgresql:// or postgres://). invalid_input: a bad schema name.
Result<PgAddress> parse_pg_uri(const std::string& uri);

// "name" with embedded quotes doubled: an SQL identifier.
std::string quote_pg_identifier(const std::string& name);

}  // namespace dtlab::store::detail
