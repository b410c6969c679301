// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The one way the readers get bytes (a file, standard input or memory) and the writers put them.
#include <atomic>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace section::detail {

/// Checks the first bytes (up to 64 KiB) of an input spooled to a temporary file; throws
/// section::Error to refuse it before the rest is read (an endless /dev/zero).
using HeadCheck = std::function<void(std::string_view head)>;

/// The bytes of a file, standard input or a buffer in memory. A file or a pipe is read in
/// blocks into one reused buffer: faster than mapping windows of the file, and a file
/// truncated while it is read is a short read, not a SIGBUS. bytes() are the unconsumed
/// bytes at hand; fetch() brings more after them.
/// Errors name the source after `component` ("read_cloud: FILE: cannot open: ..."); with no
/// component, a failed standard input is "cannot read standard input". A directory is
/// refused when opened ("FILE: is a directory").
class ByteSource {
public:
  /// Opens `path` ("-" = standard input) to be read once, as it comes (a pipe is not
  /// spooled); throws section::Error when it cannot.
  ByteSource(const std::string& path, std::string component);
  /// Opens `path` ("-" = standard input) as a regular file that can be read again and read
  /// anywhere: an input that is not one (standard input, a named pipe, a process
  /// substitution /dev/fd/N, a character device) is first copied whole into an unlinked
  /// temporary file (in TMPDIR, at most memory_limit() bytes) after `check` has seen its
  /// first bytes, and every later open of the same path reads that copy: a pipe is read
  /// once, and a pipe and a file give the same bytes out.
  ByteSource(const std::string& path, std::string component, const HeadCheck& check);
  /// A source over `bytes` (kept by the caller), named `name` in messages.
  ByteSource(std::string_view bytes, const std::string& name);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  const std::string& name() const { return name_; }  ///< the path, or "<stdin>"
  long long size() const { return size_; }           ///< bytes of a regular file; -1 when unknown (a pipe)
  /// The descriptor of a regular file of known size (which pread can read anywhere), or -1.
  int regular_fd() const;
  /// Bytes consumed since the start: the file offset of bytes() when it is a file.
  unsigned long long offset() const { return consumed_; }

  std::string_view bytes() const { return {base_ + start_, end_ - start_}; }
  void consume(std::size_t n) {
    start_ += n;
    consumed_ += n;
  }
  /// Makes up to `n` more bytes available after bytes(); returns how many (0 at the end).
  /// All `n` unless the input ends first; with `first_only`, the first bytes that come
  /// (from a pipe, what its writer has written so far).
  std::size_t fetch(std::size_t n, bool first_only = false);
  /// The next line with its '\n' (the last may lack it), valid until the next call; false
  /// at the end. A line that reaches `max_line` bytes without a '\n' is returned cut there
  /// (without '\n'), for the caller to refuse.
  bool next_line(std::string_view& line, std::size_t max_line);
  /// All the bytes not consumed yet; throws section::Error when they are more than
  /// max_input_bytes() (checked before reading for a regular file).
  std::string read_all();

private:
  void open(const std::string& path);
  [[noreturn]] void read_error() const;
  std::string name_, component_;
  std::FILE* file_ = nullptr;
  bool owned_ = false, eof_ = false;
  long long size_ = -1;
  std::unique_ptr<char[]> buf_;
  std::size_t cap_ = 0;
  const char* base_ = nullptr;  // bytes() = base_[start_, end_)
  std::size_t start_ = 0, end_ = 0;
  unsigned long long consumed_ = 0;
};

/// Reads up to `want` bytes at offset `at` (again after a signal); returns how many it got:
/// fewer at the end of the file or on an error.
std::size_t pread_full(int fd, void* buf, std::size_t want, unsigned long long at);

/// A file or standard output being written. A regular file (or a new one) is written under
/// a unique temporary name in its directory (mkstemp: created anew, never through a
/// symlink; removed by remove_temporary_files() on a signal) and renamed to its name by
/// close(), so that it appears only whole and two runs writing it do not mix their bytes;
/// the destructor removes the temporary file when close() was not reached. Anything else
/// (/dev/null, a named pipe, a terminal) is written as it goes. Errors name the file after
/// `component` with the reason ("FILE: write error: No space left on device"); with no
/// component, a failed standard output is "cannot write standard output: ...".
class ByteSink {
public:
  /// Opens `path` ("-" = standard output, after what was written through std::cout); the
  /// temporary name ends with `suffix` (for writers that choose the format by extension).
  /// Throws section::Error when it cannot.
  ByteSink(const std::string& path, std::string component, const std::string& suffix = "");
  /// Closes an unclosed file and removes its temporary name (a failure then is not reported).
  ~ByteSink();
  ByteSink(const ByteSink&) = delete;
  ByteSink& operator=(const ByteSink&) = delete;

  void write(std::string_view bytes);
  /// Pushes what is buffered to the output.
  void flush();
  /// Flushes standard output, or closes the file and gives it its name.
  void close();
  std::FILE* file() const { return file_; }
  /// The temporary name being written ("" when written as it goes).
  const std::string& temporary() const { return temporary_; }
  [[noreturn]] void write_error(int error) const;

private:
  std::string path_, component_, temporary_;
  std::FILE* file_ = nullptr;
  int slot_ = -1;  // in the registry of temporary files
};

/// Registers a temporary file for remove_temporary_files(); returns its slot (-1: not kept).
int register_temporary(const std::string& path);
/// Takes a temporary file out of the registry.
void unregister_temporary(int slot);

/// Throws `WHAT is larger than LIMIT, the most an input may take with the memory limit of
/// M (the tools' --max-memory raises it)`.
[[noreturn]] void refuse_size(const std::string& what, std::size_t limit);

/// Counts the bytes a reader holds (several threads may add) and throws `WHAT (over
/// LIMIT, ...)` once they pass `limit`.
class HeldBytes {
public:
  HeldBytes(std::size_t limit, std::string what);
  void add(std::size_t bytes);

private:
  const std::size_t limit_;
  const std::string what_;
  std::atomic<std::size_t> held_{0};
};

}  // namespace section::detail
