// Errors that come from the environment (a file, a protocol, SQLite, a shader,
// a CSV) as values: each names where it happened (file, line, column, field),
// what was expected, and its kind, set where the error is made, so callers
// decide by kind, never by message text. Programmer errors are asserts
// instead; a violated public precondition throws std::invalid_argument.
#pragma once
#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace dtlab {

// What kind of failure an Error is; it decides the exit code (app/commands.h,
// exit_code) and whether a caller may retry. Never inferred from the message.
enum class ErrorKind {
  invalid_input,  // the input is wrong (protocol, CSV, database content, an argument value)
  not_found,      // a named thing does not exist (file, participant, trial, revision)
  conflict,       // the request contradicts what is stored (answered twice, a finished session, another protocol)
  environment,    // the environment failed: I/O, SQLite, GL context, a subprocess
  busy,           // a resource is held by someone else (a database lock past its timeout, a claimed session)
  internal,       // a bug: a state the code promises never to reach
};
const char* to_string(ErrorKind kind);  // "invalid_input", "not_found", ... (stable: used in JSON)

struct Error {
  std::string file;     // path of the input at fault, empty if none
  int line = 0;         // 1-based; 0 = unknown / whole file
  int column = 0;       // 1-based; 0 = unknown
  std::string field;    // dotted path of the field at fault, e.g. "factors.transparency.levels"
  std::string message;  // what was wrong and what was expected
  ErrorKind kind = ErrorKind::invalid_input;

  // "file:line:column: field: message" with the empty parts left out.
  std::string to_string() const;
};

enum class Severity { error, warning };

// An Error that may also be a warning (validation reports both).
struct Diagnostic {
  Severity severity = Severity::error;
  Error where;
  std::string to_string() const;  // "file:line:col: error: field: message"
};

// Either a value or an Error. Access value() only after checking ok().
template <class T>
class Result {
 public:
  Result(T value) : v_(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : v_(std::move(error)) {}  // NOLINT: implicit by design
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & { assert(ok() && "Result::value() on an error: check ok() first"); return std::get<0>(v_); }
  const T& value() const& { assert(ok() && "Result::value() on an error: check ok() first"); return std::get<0>(v_); }
  T&& value() && { assert(ok() && "Result::value() on an error: check ok() first"); return std::get<0>(std::move(v_)); }
  const Error& error() const { assert(!ok() && "Result::error() on a value: check ok() first"); return std::get<1>(v_); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Error> v_;
};

// Result<void>: success or an Error.
struct Status {
  Status() = default;
  Status(Error error) : error_(std::move(error)), ok_(false) {}  // NOLINT: implicit by design
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  const Error& error() const { assert(!ok_ && "Status::error() on success"); return error_; }

 private:
  Error error_;
  bool ok_ = true;
};

}  // namespace dtlab
