// SPDX-License-Identifier: GPL-3.0-or-later
// StreamWriter: a stream split into parts, written part by part as the parts come.
#include "section/io/stream.h"

#include "io/byte_source.h"
#include "io/stream_text.h"
#include "section/error.h"

#include <cstdio>

#include <fcntl.h>
#include <sys/stat.h>

namespace section {

StreamWriter::StreamWriter(const std::string& path, const Stream& head) : path_(path) {
  // A regular file (or a new one) is written under a temporary name and renamed when
  // whole (ByteSink); anything else (/dev/null, a named pipe) is written as it is.
  out_ = std::make_unique<detail::ByteSink>(path, "");
#ifdef F_SETPIPE_SZ
  // A pipe that holds a whole part: the next tool reads it in one go, and this one
  // writes it without waiting (Linux; elsewhere, or when refused, the default stands).
  struct stat st {};
  if (::fstat(fileno(out_->file()), &st) == 0 && S_ISFIFO(st.st_mode))
    ::fcntl(fileno(out_->file()), F_SETPIPE_SZ, 1 << 20);
#endif
  out_->write(detail::format_preamble(head));
}

StreamWriter::~StreamWriter() = default;  // (the ByteSink removes an unfinished file's temporary name)

void StreamWriter::part(const std::string& label, const Stream& part) {
  if (finished_) throw Error("pipe: a part written after '# end'");
  const detail::FormattedStream f = detail::format_parts(part, "# part " + detail::one_line(label) + "\n");
  for (const auto& p : f.parts) out_->write(p);
  out_->flush();
}

void StreamWriter::finish() {
  if (finished_) return;
  out_->write("# end\n");
  out_->close();
  finished_ = true;
}

}  // namespace section
