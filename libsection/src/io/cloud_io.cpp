// SPDX-License-Identifier: GPL-3.0-or-later
#include "section/io/cloud_io.h"

#include "detail/parallel.h"
#include "io/cloud_readers.h"
#include "io/formats.h"
#include "io/text.h"
#include "section/error.h"

#include <atomic>
#include <charconv>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

namespace section {

namespace detail {

void Chunker::add_many(const Eigen::Vector3d* p, std::size_t n) {
  while (n > 0) {
    if (buf_.empty() && n >= chunk_) {
      fn_(p, chunk_);
      total_ += chunk_;
      p += chunk_;
      n -= chunk_;
      continue;
    }
    const std::size_t m = std::min(n, chunk_ - buf_.size());
    buf_.insert(buf_.end(), p, p + m);
    p += m;
    n -= m;
    if (buf_.size() == chunk_) flush();
  }
}

void fail_line(const std::string& name, std::size_t line, const std::string& what) {
  throw Error("read_cloud: " + name + ":" + std::to_string(line) + ": " + what);
}

std::size_t worker_count(int threads) {
  return threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace detail

namespace {

using detail::ByteSource;

// The check read_source makes of a text cloud's first bytes, made on a pipe's before it is
// copied (ByteSource's spool): the same message, before the rest of an endless input.
void check_head(const std::string& path, const std::string& name, std::string_view head,
                const CloudReadOptions& options) {
  if (head.empty()) return;
  if (detail::cloud_format(path, head, options.format).text)
    if (const char* why = detail::text_encoding_problem(head))
      throw Error("read_cloud: " + name + ": " + why);
}

// A cloud file ("-" = standard input) opened for reading: a pipe is copied to a temporary
// file first, so that every reader reads it as a file (and it can be read twice).
std::unique_ptr<ByteSource> open_cloud(const std::string& path, const CloudReadOptions& options) {
  const std::string name = path == "-" ? "<stdin>" : path;
  return std::make_unique<ByteSource>(
      path, "read_cloud: ", [&](std::string_view head) { check_head(path, name, head, options); });
}

// The points of `src` (named `path`) through the reader of its format, each chunk checked
// against max_coordinate unless its reader checks them itself.
std::size_t read_source(ByteSource& src, const std::string& path, const PointChunkFn& on_chunk,
                        const CloudReadOptions& options) {
  src.fetch(1 << 16);
  std::string_view buf = src.bytes();
  if (buf.empty()) throw Error("read_cloud: " + src.name() + ": empty file");
  const detail::InputFormat& format = detail::cloud_format(path, buf, options.format);
  if (format.text) {
    if (const char* why = detail::text_encoding_problem(buf))
      throw Error("read_cloud: " + src.name() + ": " + why);
    if (detail::skip_bom(buf)) src.consume(3);
  }
  // Coordinates in another unit are scaled as they come, after the checks of the file's own numbers.
  std::vector<Eigen::Vector3d> scaled;
  const PointChunkFn to_caller =
      options.scale == 1 ? on_chunk : [&](const Eigen::Vector3d* p, std::size_t n) {
        scaled.assign(p, p + n);
        for (auto& q : scaled) q *= options.scale;
        on_chunk(scaled.data(), n);
      };
  std::size_t seen = 0;
  const PointChunkFn checked = [&](const Eigen::Vector3d* p, std::size_t n) {
    bool beyond = false;
    const double* d = n ? p[0].data() : nullptr;
    for (std::size_t i = 0; i < 3 * n; ++i) beyond |= std::abs(d[i]) > detail::max_coordinate;
    for (std::size_t i = 0; beyond && i < n; ++i)
      if (p[i].cwiseAbs().maxCoeff() > detail::max_coordinate)
        throw Error("read_cloud: " + src.name() + ": point " + std::to_string(seen + i + 1) +
                    " has a coordinate beyond +-1e15 (corrupt file?)");
    seen += n;
    to_caller(p, n);
  };
  return format.read_cloud(src, options, checked, to_caller);
}

// Packed doubles of a regular file read by pread on worker threads, a chunk each; `merge`
// in file order (read_cloud_chunks_parallel).
class PackedChunks {
public:
  PackedChunks(int fd, const detail::BinaryVertices& v, const std::string& name,
               const CloudReadOptions& options)
      : fd_(fd),
        start_(v.start),
        count_(v.count),
        name_(name),
        chunk_(std::max<std::size_t>(options.chunk_points, 1)),
        chunks_(static_cast<std::size_t>((count_ + chunk_ - 1) / chunk_)),
        scale_(options.scale),
        first_bad_(chunks_) {}

  void run(const ChunkWorkFn& work, const IndexedChunkFn& merge, int threads, const ChunkFilter& wanted) {
    wanted_ = &wanted;
    const std::size_t workers = std::min<std::size_t>(chunks_, detail::worker_count(threads));
    std::vector<std::thread> pool = detail::start_threads(workers - 1, [&] { worker(work, merge); });
    worker(work, merge);
    for (auto& t : pool) t.join();
    if (error_) std::rethrow_exception(error_);
  }

private:
  void worker(const ChunkWorkFn& work, const IndexedChunkFn& merge) {
    std::vector<Eigen::Vector3d> buf;
    for (std::size_t k; (k = next_++) < chunks_;) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (k > first_bad_) break;  // an earlier chunk failed: no use reading on
      }
      try {
        if (!one(k, buf, work, merge)) break;
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (k < first_bad_) {
          first_bad_ = k;
          error_ = std::current_exception();
        }
        merged_one_.notify_all();
        break;
      }
    }
  }

  // Reads, checks and works on chunk k, then merges it after those before; false when an
  // earlier chunk failed.
  bool one(std::size_t k, std::vector<Eigen::Vector3d>& buf, const ChunkWorkFn& work,
           const IndexedChunkFn& merge) {
    if (*wanted_ && !(*wanted_)(k)) {  // passed over, in its turn
      std::unique_lock<std::mutex> lock(mutex_);
      merged_one_.wait(lock, [&] { return next_merge_ == k || first_bad_ < k; });
      if (first_bad_ < k) return false;
      ++next_merge_;
      merged_one_.notify_all();
      return true;
    }
    const unsigned long long first = static_cast<unsigned long long>(k) * chunk_;
    const std::size_t m = static_cast<std::size_t>(std::min<unsigned long long>(chunk_, count_ - first));
    buf.resize(m);
    const std::size_t got = detail::pread_full(fd_, buf.data(), 24 * m, start_ + 24 * first);
    if (got < 24 * m)
      throw Error("read_cloud: " + name_ + ": PLY file ends or cannot be read after at most " +
                  std::to_string(first + got / 24) + " of " + std::to_string(count_) +
                  " vertices (truncated file?)");
    detail::check_vertices(buf.data(), m, first, name_);
    if (scale_ != 1)
      for (auto& p : buf) p *= scale_;
    work(k, buf.data(), m, 1);
    // Merged in file order: wait for the chunks before.
    std::unique_lock<std::mutex> lock(mutex_);
    merged_one_.wait(lock, [&] { return next_merge_ == k || first_bad_ < k; });
    if (first_bad_ < k) return false;
    lock.unlock();
    merge(k, buf.data(), m);
    lock.lock();
    ++next_merge_;
    merged_one_.notify_all();
    return true;
  }

  const int fd_;
  const unsigned long long start_, count_;
  const std::string& name_;
  const std::size_t chunk_, chunks_;
  const double scale_;
  std::atomic<std::size_t> next_{0};
  std::mutex mutex_;
  std::condition_variable merged_one_;
  std::size_t next_merge_ = 0;
  std::size_t first_bad_;     // lowest chunk that failed
  std::exception_ptr error_;  // its error
  const ChunkFilter* wanted_ = nullptr;
};

}  // namespace

std::size_t read_cloud_chunks(const std::string& path, const PointChunkFn& on_chunk,
                              const CloudReadOptions& options) {
  const auto src = open_cloud(path, options);
  return read_source(*src, path, on_chunk, options);
}

std::size_t read_cloud_chunks_parallel(const std::string& path, const ChunkWorkFn& work,
                                       const IndexedChunkFn& merge, const CloudReadOptions& options,
                                       const ChunkFilter& wanted) {
  // Packed doubles in a regular file: pread anywhere, no conversion.
  const std::unique_ptr<ByteSource> src = open_cloud(path, options);
  const std::optional<detail::BinaryVertices> layout = detail::binary_vertices(*src, path, options);
  if (!layout || !layout->packed()) {
    // Anything else (its errors included) as read_cloud_chunks reads it.
    std::size_t index = 0;
    return read_cloud_chunks(
        path,
        [&](const Eigen::Vector3d* p, std::size_t n) {
          if (!wanted || wanted(index)) {
            work(index, p, n, options.threads);
            merge(index, p, n);
          }
          ++index;
        },
        options);
  }
  PackedChunks(src->regular_fd(), *layout, src->name(), options).run(work, merge, options.threads, wanted);
  return static_cast<std::size_t>(layout->count);
}

CloudPeek peek_cloud(const std::string& path, std::size_t count, const CloudReadOptions& options) {
  CloudPeek out;
  if (count == 0) return out;
  try {
    const auto src = open_cloud(path, options);
    const auto v = detail::binary_vertices(*src, path, options);
    if (!v || v->record > 4096) return out;
    const unsigned long long m = std::min<unsigned long long>(count, v->count);
    unsigned char rec[4096];
    out.points.reserve(static_cast<std::size_t>(m));
    for (unsigned long long i = 0; i < m; ++i) {
      // Vertex i of m evenly spaced ones, moved within its stride by a golden-ratio
      // sequence: no lattice from a regular scan order, and the same points every time.
      const double jitter = std::fmod(0.5 + 0.6180339887498949 * double(i), 1.0);
      const unsigned long long k = std::min<unsigned long long>(
          v->count - 1, static_cast<unsigned long long>((double(i) + jitter) * double(v->count) / double(m)));
      if (detail::pread_full(src->regular_fd(), rec, v->record, v->start + k * v->record) < v->record)
        return {};
      const Eigen::Vector3d p = v->point(rec);
      if (p.allFinite() && p.cwiseAbs().maxCoeff() <= detail::max_coordinate)
        out.points.push_back(options.scale * p);
    }
    out.total = v->count;
  } catch (const Error&) {
    return {};
  }
  return out;
}

Cloud read_cloud(const std::string& path, const CloudReadOptions& options) {
  Cloud cloud;
  read_cloud_chunks(
      path,
      [&](const Eigen::Vector3d* p, std::size_t n) { cloud.points.insert(cloud.points.end(), p, p + n); },
      options);
  return cloud;
}

Cloud parse_cloud(std::string_view bytes, const std::string& name, const CloudReadOptions& options) {
  ByteSource src(bytes, name);
  Cloud cloud;
  read_source(
      src, name,
      [&](const Eigen::Vector3d* p, std::size_t n) { cloud.points.insert(cloud.points.end(), p, p + n); },
      options);
  return cloud;
}

void write_cloud(const std::string& path, const Cloud& cloud) {
  detail::ByteSink out(path, "write_cloud: ");
  if (detail::extension(path) == "ply") {
    out.write("ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.points.size()) +
              "\nproperty double x\nproperty double y\nproperty double z\nend_header\n");
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "packed Vector3d");
    out.write(
        {reinterpret_cast<const char*>(cloud.points.data()), sizeof(Eigen::Vector3d) * cloud.points.size()});
  } else {
    std::string text;
    char b[32];
    for (const auto& p : cloud.points) {
      for (int k = 0; k < 3; ++k) {
        const auto r = std::to_chars(b, b + sizeof b, p[k]);
        text.append(b, r.ptr);
        text += k == 2 ? '\n' : ' ';
      }
      if (text.size() > (1 << 22)) {
        out.write(text);
        text.clear();
      }
    }
    out.write(text);
  }
  out.close();
}

}  // namespace section
