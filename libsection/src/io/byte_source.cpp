// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/byte_source.h"

#include "section/error.h"
#include "section/io/limits.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <map>
#include <mutex>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

namespace section::detail {

namespace {

// The termination signals the tools clean up after, held off while a temporary file is
// created and registered or unlinked: one landing in between would leave the file behind,
// since the handler removes registered files only. A held signal is delivered when the
// mask returns.
class HeldSignals {
public:
  HeldSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&set, sig);
    held_ = ::pthread_sigmask(SIG_BLOCK, &set, &old_) == 0;
  }
  ~HeldSignals() {
    if (held_) ::pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  HeldSignals(const HeldSignals&) = delete;
  HeldSignals& operator=(const HeldSignals&) = delete;

private:
  sigset_t old_{};
  bool held_ = false;
};

std::string reason(int error) {
  return std::strerror(error);
}

// A new descriptor of the file open as `fd`, with an offset of its own (two readers of one
// spooled input do not move each other's place); a duplicate when /proc is not there.
int reopen(int fd) {
  const std::string self = "/proc/self/fd/" + std::to_string(fd);
  const int again = ::open(self.c_str(), O_RDONLY | O_CLOEXEC);
  if (again >= 0) return again;
  const int dup = ::dup(fd);
  if (dup >= 0) ::lseek(dup, 0, SEEK_SET);
  return dup;
}

// A regular file that is not at its start (standard input redirected after a read) is
// spooled too: readers read a file from its first byte.
bool readable_in_place(int fd) {
  struct stat st {};
  return ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::lseek(fd, 0, SEEK_CUR) == 0;
}

// Copies the input `path` ("-" = standard input) into an unlinked temporary file in TMPDIR:
// `check` sees its first 64 KiB first; at most memory_limit() bytes. Returns its descriptor.
int spool(const std::string& path, const std::string& name, const std::string& component,
          const HeadCheck& check) {
  const int in = path == "-" ? 0 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) throw Error(component + path + ": cannot open: " + reason(errno));
  struct Closer {
    int fd;
    ~Closer() {
      if (fd > 0) ::close(fd);
    }
  } closer{path == "-" ? -1 : in};
  const char* dir = std::getenv("TMPDIR");
  std::string pattern = std::string(dir && *dir ? dir : "/tmp") + "/libsection-spool-XXXXXX";
  int out = -1;
  {
    const HeldSignals held;
    out = ::mkstemp(pattern.data());
    if (out >= 0) ::unlink(pattern.c_str());  // gone with the last descriptor, even after a kill
  }
  if (out < 0)
    throw Error(component + name + ": cannot make a temporary copy in " + pattern + ": " + reason(errno));
  const auto fail = [&](const std::string& what) {
    ::close(out);
    throw Error(component + name + ": " + what);
  };
  const std::size_t limit = memory_limit();
  std::unique_ptr<char[]> buf(new char[1 << 20]);
  std::size_t total = 0, head = 0;
  bool checked = false;
  while (true) {
    // The first 64 KiB are gathered and checked before anything is written.
    const std::size_t want = checked ? (1 << 20) : (1 << 16) - head;
    const ssize_t got = ::read(in, buf.get() + (checked ? 0 : head), want);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0)
      fail(path == "-" ? "cannot read standard input: " + reason(errno) : "read error: " + reason(errno));
    if (!checked) {
      head += std::size_t(got);
      if (got > 0 && head < (1 << 16)) continue;
      if (check) {
        try {
          check(std::string_view(buf.get(), head));
        } catch (...) {
          ::close(out);
          throw;
        }
      }
      checked = true;
    }
    const std::size_t n = head ? head : std::size_t(got);
    head = 0;
    if (n == 0) break;
    if ((total += n) > limit) {
      ::close(out);
      refuse_size(component + name, limit);
    }
    for (std::size_t done = 0; done < n;) {
      const ssize_t w = ::write(out, buf.get() + done, n - done);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0)
        fail("cannot copy it to a temporary file in " + std::string(dir && *dir ? dir : "/tmp") + ": " +
             reason(errno) + " (set TMPDIR, or give the file by path)");
      done += std::size_t(w);
    }
  }
  return out;
}

// The spooled inputs of the process, by path: each is copied once, and one that failed
// fails again with the same error (opened again, a pipe would hang or give other bytes).
int spooled(const std::string& path, const std::string& name, const std::string& component,
            const HeadCheck& check) {
  static std::mutex mutex;
  static std::map<std::string, std::pair<int, std::exception_ptr>> files;
  std::lock_guard<std::mutex> lock(mutex);
  const auto at = files.find(path);
  if (at != files.end()) {
    if (at->second.second) std::rethrow_exception(at->second.second);
    return at->second.first;
  }
  try {
    const int fd = spool(path, name, component, check);
    files[path] = {fd, nullptr};
    return fd;
  } catch (...) {
    files[path] = {-1, std::current_exception()};
    throw;
  }
}

}  // namespace

ByteSource::ByteSource(const std::string& path, std::string component)
    : name_(path == "-" ? "<stdin>" : path), component_(std::move(component)) {
  if (path == "-") {
    file_ = stdin;
    return;
  }
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw Error(component_ + path + ": cannot open: " + reason(errno));
  owned_ = true;
  open(path);
}

ByteSource::ByteSource(const std::string& path, std::string component, const HeadCheck& check)
    : name_(path == "-" ? "<stdin>" : path), component_(std::move(component)) {
  int fd = -1;
  if (path == "-") {
    fd = readable_in_place(0) ? reopen(0) : reopen(spooled(path, name_, component_, check));
  } else {
    // Told apart before it is opened: a named pipe opened twice loses its writer.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
      throw Error(component_ + path + ": is a directory");
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
      fd = reopen(spooled(path, name_, component_, check));
    } else {
      fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) throw Error(component_ + path + ": cannot open: " + reason(errno));
    }
  }
  if (fd < 0 || !(file_ = ::fdopen(fd, "rb"))) {
    if (fd >= 0) ::close(fd);
    throw Error(component_ + name_ + ": cannot open: " + reason(errno));
  }
  owned_ = true;
  open(path);
}

void ByteSource::open(const std::string& path) {
  struct stat st {};
  if (::fstat(fileno(file_), &st) != 0) return;
  if (S_ISDIR(st.st_mode)) {
    std::fclose(file_);
    file_ = nullptr;
    throw Error(component_ + path + ": is a directory");
  }
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
  const std::string why = errno ? ": " + reason(errno) : "";
  throw Error(component_.empty() && file_ == stdin ? "cannot read standard input" + why
                                                   : component_ + name_ + ": read error" + why);
}

namespace {

// Reads up to n bytes from fd into buf: until all came or the end, or with `first_only` until
// the first bytes come. Returns how many, or -1 on an error (errno tells). The descriptor is
// read, never the FILE's buffer: a read would not see what stdio had buffered ahead of it.
long read_fd(int fd, char* buf, std::size_t n, bool first_only) {
  std::size_t got = 0;
  while (got < n) {
    const ssize_t r = ::read(fd, buf + got, n - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return -1;
    if (r == 0) break;
    got += std::size_t(r);
    if (first_only) break;
  }
  return long(got);
}

}  // namespace

std::size_t ByteSource::fetch(std::size_t n, bool first_only) {
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
  errno = 0;
  const long got = read_fd(fileno(file_), buf_.get() + end_, n, first_only);
  if (got < 0) read_error();
  end_ += std::size_t(got);
  return std::size_t(got);
}

bool ByteSource::next_line(std::string_view& line, std::size_t max_line) {
  constexpr std::size_t block = std::size_t(1) << 20;
  std::size_t searched = 0;  // bytes at hand known to hold no '\n'
  while (true) {
    const std::string_view at = bytes();
    const char* nl =
        at.size() > searched
            ? static_cast<const char*>(std::memchr(at.data() + searched, '\n', at.size() - searched))
            : nullptr;
    if (!nl && at.size() >= max_line) {
      line = at.substr(0, max_line);
      consume(line.size());
      return true;
    }
    if (nl || eof_) {
      if (at.empty()) return false;
      line = at.substr(0, nl ? std::size_t(nl - at.data()) + 1 : at.size());
      consume(line.size());
      return true;
    }
    searched = at.size();
    // What a pipe's writer has written so far is taken: a stage of the pipe works on each
    // part as it comes, not once a whole block of the parts after it has come too.
    if (fetch(std::min(block, max_line), true) == 0) eof_ = true;
  }
}

std::string ByteSource::read_all() {
  const std::size_t limit = max_input_bytes();
  if (size_ >= 0 && static_cast<unsigned long long>(size_) - consumed_ > limit)
    refuse_size(component_ + name_, limit);
  std::string data(bytes());
  consume(data.size());
  if (!file_) return data;
  // Block reads straight into the string, doubling it when full (a character iterator over
  // std::cin took twice as long as parsing a stream).
  std::size_t size = data.size(), n;
  data.resize(std::max(size, std::size_t(1) << 20));
  errno = 0;
  while (true) {
    if (size == data.size()) {
      if (size > limit) refuse_size(component_ + name_, limit);
      data.resize(std::min(2 * data.size(), limit + 1));
    }
    const long got = read_fd(fileno(file_), &data[size], data.size() - size, false);
    if (got < 0) read_error();
    if ((n = std::size_t(got)) == 0) break;
    size += n;
  }
  if (size > limit) refuse_size(component_ + name_, limit);
  data.resize(size);
  consumed_ += size;
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

namespace {

// The permissions a new file gets (0666 less the umask), read once.
mode_t new_file_mode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(022);
    ::umask(mask);
    return 0666 & ~mask;
  }();
  return mode;
}

// A unique file created next to `path` (PATH.XXXXXX.partialSUFFIX), with the permissions of
// the file it replaces, or those of a new file. Returns its descriptor and name, or -1.
int make_temporary(const std::string& path, const std::string& suffix, std::string& name) {
  const std::string tail = ".partial" + suffix;
  name = path + ".XXXXXX" + tail;
  const int fd = ::mkstemps(name.data(), static_cast<int>(tail.size()));
  if (fd < 0) return -1;
  struct stat st {};
  ::fchmod(fd,
           ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) ? (st.st_mode & 07777) : new_file_mode());
  return fd;
}

}  // namespace

ByteSink::ByteSink(const std::string& path, std::string component, const std::string& suffix)
    : path_(path), component_(std::move(component)) {
  if (path == "-") {
    std::cout.flush();  // anything written through std::cout before goes first
    file_ = stdout;
    return;
  }
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw Error(component_ + path + ": is a directory");
  if (!exists || S_ISREG(st.st_mode)) {
    int fd = -1;
    {
      const HeldSignals held;
      fd = make_temporary(path, suffix, temporary_);
      if (fd >= 0) slot_ = register_temporary(temporary_);
    }
    if (fd >= 0) {
      if (!(file_ = ::fdopen(fd, "wb"))) {
        const int e = errno;
        ::close(fd);
        ::unlink(temporary_.c_str());
        unregister_temporary(slot_);
        throw Error(component_ + path + ": cannot open for writing: " + reason(e));
      }
      return;
    }
    temporary_.clear();
    // A directory that takes no new file may still let the file itself be written.
    if (!exists) throw Error(component_ + path + ": cannot open for writing: " + reason(errno));
  }
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw Error(component_ + path + ": cannot open for writing: " + reason(errno));
}

ByteSink::~ByteSink() {
  if (file_ && file_ != stdout) std::fclose(file_);
  if (!temporary_.empty()) {
    ::unlink(temporary_.c_str());
    unregister_temporary(slot_);
  }
}

void ByteSink::write_error(int error) const {
  const std::string why = error ? ": " + reason(error) : "";
  throw Error(component_.empty() && path_ == "-" ? "cannot write standard output" + why
                                                 : component_ + path_ + ": write error" + why);
}

void ByteSink::write(std::string_view bytes) {
  errno = 0;
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) write_error(errno);
}

void ByteSink::flush() {
  errno = 0;
  if (std::fflush(file_) != 0) write_error(errno);
}

void ByteSink::close() {
  if (file_ == stdout) return flush();
  errno = 0;
  const bool bad = std::fclose(file_) != 0;
  const int error = errno;
  file_ = nullptr;
  if (bad) write_error(error);
  if (temporary_.empty()) return;
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    throw Error(component_ + path_ + ": cannot give the written file its name: " + reason(e));
  }
  unregister_temporary(slot_);
  temporary_.clear();
}

}  // namespace section::detail
