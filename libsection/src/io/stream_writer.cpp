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
  if (path == "-") {
    out_ = std::make_unique<detail::ByteSink>(path, "");
    // A pipe that holds a whole part: the next tool reads it in one go, and this one
    // writes it without waiting (Linux; elsewhere, or when refused, the default stands).
#ifdef F_SETPIPE_SZ
    struct stat st {};
    if (::fstat(fileno(stdout), &st) == 0 && S_ISFIFO(st.st_mode))
      ::fcntl(fileno(stdout), F_SETPIPE_SZ, 1 << 20);
#endif
  } else {
    // A regular file (or a new one) is written under a temporary name and renamed when
    // whole; anything else (/dev/null, a named pipe) is written as it is.
    struct stat st {};
    const bool special = ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
    if (!special) temporary_ = path + ".partial";
    try {
      out_ = std::make_unique<detail::ByteSink>(path, "", temporary_);
    } catch (const Error&) {
      if (special) throw;
      // A directory that takes no new file may still let the file itself be written.
      temporary_.clear();
      out_ = std::make_unique<detail::ByteSink>(path, "");
    }
  }
  out_->write(detail::format_preamble(head));
}

StreamWriter::~StreamWriter() {
  if (out_ && out_->file() && out_->file() != stdout) {
    out_.reset();  // closes the file
    if (!temporary_.empty()) std::remove(temporary_.c_str());
  }
}

void StreamWriter::part(const std::string& label, const Stream& part) {
  if (finished_) throw Error("pipe: a part written after '# end'");
  const detail::FormattedStream f = detail::format_parts(part, "# part " + detail::one_line(label) + "\n");
  for (const auto& p : f.parts) out_->write(p);
  out_->flush();
}

void StreamWriter::finish() {
  if (finished_) return;
  out_->write("# end\n");
  if (out_->file() == stdout) {
    out_->flush();
  } else {
    bool bad = false;
    try {
      out_->close();
    } catch (const Error&) {
      bad = true;
    }
    if (bad || (!temporary_.empty() && std::rename(temporary_.c_str(), path_.c_str()) != 0)) {
      if (!temporary_.empty()) std::remove(temporary_.c_str());
      throw Error(path_ + ": write error");
    }
  }
  finished_ = true;
}

}  // namespace section
