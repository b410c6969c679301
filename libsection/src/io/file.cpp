// SPDX-License-Identifier: GPL-3.0-or-later
// Whole files in and out.
#include "section/io/file.h"

#include "io/byte_source.h"

namespace section {

std::string read_file(const std::string& path) {
  return detail::ByteSource(path, "").read_all();
}

void write_file(const std::string& path, const std::string& bytes) {
  detail::ByteSink out(path, "");
  out.write(bytes);
  out.close();
}

}  // namespace section
