// Wall-clock timestamps as stored in the database: ISO-8601 UTC with
// milliseconds, "2024-05-01T12:34:56.789Z", fixed width so that text order
// is time order. Pure functions; never reads the local time zone.
#pragma once
#include <chrono>
#include <optional>
#include <string>

namespace dtlab::store::detail {

std::string iso8601_utc(std::chrono::system_clock::time_point t);  // fixed 24 characters
inline std::string now_iso8601_utc() { return iso8601_utc(std::chrono::system_clock::now()); }
// The time point of such a timestamp; nullopt when `text` is not one.
std::optional<std::chrono::system_clock::time_point> parse_iso8601_utc(const std::string& text);

// The GLOB pattern the schema's CHECK constraints use for such timestamps.
inline constexpr const char* kIsoGlob =
    "'[0-9][0-9][0-9][0-9]-[0-1][0-9]-[0-3][0-9]T[0-2][0-9]:[0-5][0-9]:[0-6][0-9].[0-9][0-9][0-9]Z'";

}  // namespace dtlab::store::detail
