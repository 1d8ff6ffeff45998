// SPDX-License-Identifier: LGPL-3.0-or-later
#include "safe_write.hpp"
#include <cerrno>
#include <fcntl.h>
#include <system_error>
#include <unistd.h>

namespace breastsim
{
void write_file_nofollow(const std::filesystem::path& file, const std::string& text, Existing existing)
{
  const int flags = O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC
                    | (existing == Existing::refuse ? O_EXCL : O_TRUNC);
  const int fd = ::open(file.c_str(), flags, 0644);
  if (fd < 0)
    throw std::system_error(errno, std::generic_category(), file.string());
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0)
  {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      throw std::system_error(err, std::generic_category(), file.string());
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0)
    throw std::system_error(errno, std::generic_category(), file.string());
}
} // namespace breastsim
