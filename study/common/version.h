// dtlab version and build identity. Every study database records these, so a
// result can always be traced to the code that produced it. Pure data; safe to
// call from anywhere at any time.
#pragma once
#include <string_view>

namespace dtlab {

std::string_view version();     // semantic version, e.g. "0.1.0"
std::string_view git_commit();  // short commit hash at configure time, "-dirty" if the tree had changes
std::string_view version_string();  // "dtlab 0.1.0 (commit abc123)" for --version and the store

}  // namespace dtlab
