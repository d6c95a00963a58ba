// Formatting of environment errors; see error.h.
#include "study/common/error.h"

namespace dtlab {

const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_input: return "invalid_input";
    case ErrorKind::not_found: return "not_found";
    case ErrorKind::conflict: return "conflict";
    case ErrorKind::environment: return "environment";
    case ErrorKind::busy: return "busy";
    case ErrorKind::internal: return "internal";
  }
  return "internal";
}

std::string Error::to_string() const {
  std::string s;
  if (!file.empty()) {
    s += file;
    if (line > 0) {
      s += ":" + std::to_string(line);
      if (column > 0) s += ":" + std::to_string(column);
    }
    s += ": ";
  }
  if (!field.empty()) s += field + ": ";
  s += message;
  return s;
}

std::string Diagnostic::to_string() const {
  std::string s;
  if (!where.file.empty()) {
    s += where.file;
    if (where.line > 0) {
      s += ":" + std::to_string(where.line);
      if (where.column > 0) s += ":" + std::to_string(where.column);
    }
    s += ": ";
  }
  s += severity == Severity::error ? "error: " : "warning: ";
  if (!where.field.empty()) s += where.field + ": ";
  s += where.message;
  return s;
}

}  // namespace dtlab
