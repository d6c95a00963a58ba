// Writing a file whole or not at all: the content goes to a temporary file
// beside the target, which is renamed over the target only once complete, so
// a reader (or a crash) never sees half a file and a failed write leaves the
// old file untouched. The one home of "write to a temp file, then rename".
#pragma once
#include <functional>
#include <ostream>
#include <string>

#include "study/common/error.h"

namespace dtlab {

// Calls write(out) on a stream to "<path>.tmp-<pid>", then renames it to `path`. An Error from
// `write` is returned as is (nothing is renamed); failing I/O is an environment Error naming the file.
Status write_file_atomically(const std::string& path, const std::function<Status(std::ostream&)>& write);

}  // namespace dtlab
