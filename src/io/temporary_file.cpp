#include "io/temporary_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/hdf5_file.hpp"

namespace tirefe::io {

bool empty_or_begins_with(const std::string& path, const std::string& signature) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat status {};
  std::string head(signature.size(), '\0');
  const bool regular = ::fstat(fd, &status) == 0 && S_ISREG(status.st_mode);
  const ssize_t read = regular ? ::read(fd, head.data(), head.size()) : -1;
  ::close(fd);
  return read == 0 || (read == static_cast<ssize_t>(head.size()) && head == signature);
}

void clear_for_temporary(const std::string& path, const std::string& signature) {
  struct stat status {};
  if (::lstat(path.c_str(), &status) != 0) return;  // nothing there
  const char* what = S_ISLNK(status.st_mode)                  ? "a symbolic link, which tirefe never writes through"
                     : !S_ISREG(status.st_mode)               ? "not a regular file"
                     : !empty_or_begins_with(path, signature) ? "a file tirefe did not write"
                                                              : nullptr;
  if (what)
    throw IoError("'" + path + "' is in the way of the temporary file tirefe writes there: it is " + what +
                  "; remove it");
  if (::unlink(path.c_str()) != 0 && errno != ENOENT)
    throw IoError("cannot remove the leftover '" + path + "': " + std::strerror(errno));
}

int create_new_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (fd < 0) throw IoError("cannot create '" + path + "': " + std::strerror(errno));
  return fd;
}

}  // namespace tirefe::io
