#pragma once
// The one way the readers get bytes (a file, standard input or memory) and the writers put them.
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

namespace section::detail {

/// The bytes of a file, standard input or a buffer in memory. A file or a pipe is read in
/// blocks into one reused buffer: faster than mapping windows of the file, and a file
/// truncated while it is read is a short read, not a SIGBUS. bytes() are the unconsumed
/// bytes at hand; fetch() brings more after them.
/// Errors name the source after `component` ("read_cloud: FILE: cannot open: ..."); with no
/// component, a failed standard input is "cannot read standard input".
class ByteSource {
public:
  /// Opens `path` ("-" = standard input); throws section::Error when it cannot.
  ByteSource(const std::string& path, std::string component);
  /// A source over `bytes` (kept by the caller), named `name` in messages.
  ByteSource(std::string_view bytes, const std::string& name);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  const std::string& name() const { return name_; }  ///< the path, or "<stdin>"
  bool is_directory() const { return directory_; }
  long long size() const { return size_; }  ///< bytes of a regular file; -1 when unknown (a pipe)
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
  std::size_t fetch(std::size_t n);
  /// The next line with its '\n' (the last may lack it), valid until the next call; false
  /// at the end.
  bool next_line(std::string_view& line);
  /// All the bytes not consumed yet.
  std::string read_all();

private:
  [[noreturn]] void read_error() const;
  std::string name_, component_;
  std::FILE* file_ = nullptr;
  bool owned_ = false, directory_ = false, eof_ = false;
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

/// A file or standard output being written. Errors name it after `component` as ByteSource's
/// do; with no component, a failed standard output is "cannot write standard output".
class ByteSink {
public:
  /// Opens `path` ("-" = standard output, after what was written through std::cout) or, when
  /// given, `open_as` (a temporary name) under the name `path`; throws section::Error when it
  /// cannot.
  ByteSink(const std::string& path, std::string component, const std::string& open_as = "");
  /// Closes an unclosed file (a failure then is not reported).
  ~ByteSink();
  ByteSink(const ByteSink&) = delete;
  ByteSink& operator=(const ByteSink&) = delete;

  void write(std::string_view bytes);
  /// Pushes what is buffered to the output.
  void flush();
  /// Flushes standard output or closes the file.
  void close();
  std::FILE* file() const { return file_; }
  [[noreturn]] void write_error() const;

private:
  std::string path_, component_;
  std::FILE* file_ = nullptr;
};

}  // namespace section::detail
