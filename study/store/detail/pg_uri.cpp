// Parsing a PostgreSQL study URI; see pg_uri.h. libpq parses the rest of the
// URI itself when it connects; here only `schema` is taken out and any
// password is left out of the display name.
#include "study/store/detail/pg_uri.h"

#include <vector>

namespace dtlab::store::detail {
namespace {

std::string percent_decode(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size()) {
      const std::string hex = s.substr(i + 1, 2);
      char* end = nullptr;
      const long v = std::strtol(hex.c_str(), &end, 16);
      if (end == hex.c_str() + 2) {
        out += static_cast<char>(v);
        i += 2;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

bool valid_schema(const std::string& s) {
  if (s.empty() || s.size() > 63 || s.rfind("pg_", 0) == 0) return false;
  if (!((s[0] >= 'a' && s[0] <= 'z') || s[0] == '_')) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

std::int32_t fnv1a32(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return static_cast<std::int32_t>(h);
}

}  // namespace

std::string quote_pg_identifier(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

Result<PgAddress> parse_pg_uri(const std::string& uri) {
  PgAddress a;
  a.schema = "public";
  const auto scheme_end = uri.find("://") + 3;
  const auto query_at = uri.find('?', scheme_end);
  const std::string base = uri.substr(0, query_at);
  std::vector<std::string> kept, shown;
  if (query_at != std::string::npos) {
    const std::string query = uri.substr(query_at + 1);
    std::size_t from = 0;
    while (from <= query.size()) {
      const auto amp = query.find('&', from);
      const std::string param = query.substr(from, amp == std::string::npos ? std::string::npos : amp - from);
      from = amp == std::string::npos ? query.size() + 1 : amp + 1;
      if (param.empty()) continue;
      const auto eq = param.find('=');
      const std::string key = param.substr(0, eq);
      if (key == "schema") {
        a.schema = eq == std::string::npos ? "" : percent_decode(param.substr(eq + 1));
        continue;
      }
      kept.push_back(param);
      if (key != "password") shown.push_back(param);
    }
  }
  if (!valid_schema(a.schema))
    return Error{uri.substr(0, scheme_end) + "...", 0, 0, "schema",
                 "\"" + a.schema + "\" is not a schema name dtlab uses: 1-63 lowercase letters, digits and _, "
                 "starting with a letter or _, not pg_*",
                 ErrorKind::invalid_input};
  // The authority's user information may hold a password: user:password@host.
  const auto path_at = base.find('/', scheme_end);
  const std::string authority = base.substr(scheme_end, path_at == std::string::npos ? std::string::npos : path_at - scheme_end);
  std::string shown_authority = authority;
  if (const auto at = authority.rfind('@'); at != std::string::npos) {
    const std::string user = authority.substr(0, at);
    shown_authority = user.substr(0, user.find(':')) + authority.substr(at);
  }
  a.conninfo = base;
  for (std::size_t i = 0; i < kept.size(); ++i) a.conninfo += (i ? "&" : "?") + kept[i];
  a.display = base.substr(0, scheme_end) + shown_authority +
              (path_at == std::string::npos ? std::string() : base.substr(path_at));
  shown.push_back("schema=" + a.schema);
  for (std::size_t i = 0; i < shown.size(); ++i) a.display += (i ? "&" : "?") + shown[i];
  a.lock_key = fnv1a32(a.schema);
  return a;
}

}  // namespace dtlab::store::detail
