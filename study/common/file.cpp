// write_file_atomically (file.h).
#include "study/common/file.h"

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

namespace dtlab {

Status write_file_atomically(const std::string& path, const std::function<Status(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  std::error_code ec;
  Status st;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      return Error{path, 0, 0, "", std::string("cannot write here: ") + std::strerror(errno), ErrorKind::environment};
    st = write(out);
    out.flush();
    if (st && !out) st = Error{path, 0, 0, "", "writing the file failed (disk full?)", ErrorKind::environment};
  }
  if (!st) {
    fs::remove(tmp, ec);
    return st;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return Error{path, 0, 0, "", "cannot move the finished file into place: " + ec.message(), ErrorKind::environment};
  }
  return {};
}

}  // namespace dtlab
