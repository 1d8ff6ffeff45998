// SPDX-License-Identifier: LGPL-3.0-or-later
#include "result_archive.hpp"
#include "output_target.hpp"
#include <cstring>
#include <ctime>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
/// The 512-byte ustar header of a regular file.
std::string tar_header(const std::string& name, std::size_t size, std::time_t mtime)
{
  std::string h(512, '\0');
  if (name.size() > 99)
    throw std::runtime_error("file name too long for the archive: " + name);
  auto put = [&h](std::size_t at, const std::string& text) { std::memcpy(&h[at], text.data(), text.size()); };
  put(0, name);
  put(100, "0000644");
  put(108, "0000000");
  put(116, "0000000");
  put(124, fmt::format("{:011o}", size));
  put(136, fmt::format("{:011o}", static_cast<unsigned long>(mtime)));
  put(148, "        "); // checksum field counts as spaces
  h[156] = '0';
  put(257, "ustar");
  put(263, "00");
  unsigned sum = 0;
  for (unsigned char c : h)
    sum += c;
  put(148, fmt::format("{:06o}", sum));
  h[154] = '\0';
  h[155] = ' ';
  return h;
}
} // namespace

std::string result_archive(const fs::path& result_dir, const std::string& prefix, std::size_t max_bytes)
{
  const fs::path root = fs::weakly_canonical(result_dir);
  const auto marker = read_marker(root);
  std::string tar;
  std::size_t content = 0;
  for (const auto& f : marker.value("files", nlohmann::json::array()))
  {
    const fs::path file = fs::weakly_canonical(root / f.get<std::string>());
    const auto rel = file.lexically_relative(root);
    if (rel.empty() || *rel.begin() == ".." || !fs::is_regular_file(file))
      throw std::runtime_error("the result lists a file outside its folder or missing: " + f.get<std::string>());
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    const std::string data = s.str();
    if ((content += data.size()) > max_bytes)
      throw std::runtime_error(fmt::format("the result folder exceeds {} MB: download its files one by one",
                                           max_bytes >> 20));
    tar += tar_header(prefix + "/" + rel.generic_string(), data.size(), std::time(nullptr));
    tar += data;
    tar.append((512 - data.size() % 512) % 512, '\0');
  }
  tar.append(1024, '\0'); // two empty blocks end the archive
  return tar;
}
} // namespace breastsim::app
