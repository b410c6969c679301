#include "io/byte_source.h"

#include "section/error.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>

#include <sys/stat.h>
#include <unistd.h>

namespace section::detail {

ByteSource::ByteSource(const std::string& path, std::string component)
    : name_(path == "-" ? "<stdin>" : path), component_(std::move(component)) {
  if (path == "-") {
    file_ = stdin;
    return;
  }
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw Error(component_ + path + ": cannot open: " + std::strerror(errno));
  owned_ = true;
  struct stat st {};
  if (::fstat(fileno(file_), &st) == 0) directory_ = S_ISDIR(st.st_mode);
  if (S_ISREG(st.st_mode) && st.st_size > 0)  // (files of /proc claim 0 bytes: size unknown)
    size_ = static_cast<long long>(st.st_size);
}

ByteSource::ByteSource(std::string_view bytes, const std::string& name) : name_(name) {
  size_ = static_cast<long long>(bytes.size());
  base_ = bytes.data();
  end_ = bytes.size();
}

ByteSource::~ByteSource() {
  if (owned_ && file_) std::fclose(file_);
}

int ByteSource::regular_fd() const {
  return owned_ && file_ && size_ > 0 ? fileno(file_) : -1;
}

void ByteSource::read_error() const {
  throw Error(component_.empty() && file_ == stdin ? std::string("cannot read standard input")
                                                   : component_ + name_ + ": read error");
}

std::size_t ByteSource::fetch(std::size_t n) {
  if (!file_) return 0;  // in memory: all of it is at hand
  // Keep the unconsumed bytes at the front of the buffer, then read after them.
  const std::size_t keep = end_ - start_;
  if (keep + n > cap_) {
    cap_ = std::max(keep + n, 2 * cap_);
    std::unique_ptr<char[]> bigger(new char[cap_]);
    if (keep) std::memcpy(bigger.get(), base_ + start_, keep);
    buf_ = std::move(bigger);
  } else if (keep && start_) {
    std::memmove(buf_.get(), base_ + start_, keep);
  }
  base_ = buf_.get();
  start_ = 0;
  end_ = keep;
  const std::size_t got = std::fread(buf_.get() + end_, 1, n, file_);
  end_ += got;
  if (got == 0 && std::ferror(file_)) read_error();
  return got;
}

bool ByteSource::next_line(std::string_view& line) {
  constexpr std::size_t block = std::size_t(1) << 20;
  while (true) {
    const std::string_view at = bytes();
    const char* nl = at.empty() ? nullptr : static_cast<const char*>(std::memchr(at.data(), '\n', at.size()));
    if (nl || eof_) {
      if (at.empty()) return false;
      line = at.substr(0, nl ? std::size_t(nl - at.data()) + 1 : at.size());
      consume(line.size());
      return true;
    }
    if (fetch(block) == 0) eof_ = true;
  }
}

std::string ByteSource::read_all() {
  std::string data(bytes());
  consume(data.size());
  if (!file_) return data;
  // Block reads straight into the string, doubling it when full (a character iterator over
  // std::cin took twice as long as parsing a stream).
  std::size_t size = data.size(), n;
  data.resize(std::max(size, std::size_t(1) << 20));
  while (true) {
    if (size == data.size()) data.resize(2 * data.size());
    if ((n = std::fread(&data[size], 1, data.size() - size, file_)) == 0) break;
    size += n;
  }
  data.resize(size);
  consumed_ += size;
  if (std::ferror(file_)) read_error();
  return data;
}

std::size_t pread_full(int fd, void* buf, std::size_t want, unsigned long long at) {
  char* p = static_cast<char*>(buf);
  std::size_t got_all = 0;
  while (got_all < want) {
    const ssize_t got = ::pread(fd, p + got_all, want - got_all, static_cast<off_t>(at + got_all));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    got_all += std::size_t(got);
  }
  return got_all;
}

ByteSink::ByteSink(const std::string& path, std::string component, const std::string& open_as)
    : path_(path), component_(std::move(component)) {
  if (path == "-") {
    std::cout.flush();  // anything written through std::cout before goes first
    file_ = stdout;
    return;
  }
  file_ = std::fopen((open_as.empty() ? path : open_as).c_str(), "wb");
  if (!file_) throw Error(component_ + path + ": cannot open for writing: " + std::strerror(errno));
}

ByteSink::~ByteSink() {
  if (file_ && file_ != stdout) std::fclose(file_);
}

void ByteSink::write_error() const {
  throw Error(component_.empty() && path_ == "-" ? std::string("cannot write standard output")
                                                 : component_ + path_ + ": write error");
}

void ByteSink::write(std::string_view bytes) {
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) write_error();
}

void ByteSink::flush() {
  if (std::fflush(file_) != 0) write_error();
}

void ByteSink::close() {
  if (file_ == stdout) return flush();
  const bool bad = std::fclose(file_) != 0;
  file_ = nullptr;
  if (bad) write_error();
}

}  // namespace section::detail
