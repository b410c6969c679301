// SPDX-License-Identifier: GPL-3.0-or-later
// The resource policy: the memory limit and what it bounds, and the registry of the
// temporary files of outputs (removed by a signal handler).
#include "section/io/limits.h"

#include "io/byte_source.h"
#include "section/error.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include <sys/resource.h>
#include <unistd.h>

namespace section {

namespace {

std::atomic<std::size_t> chosen_limit{0};

// The cgroup's memory limit (v2, else v1), or the largest size_t when none is set.
std::size_t cgroup_limit() {
  for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    unsigned long long v = 0;
    if (in >> v && v > 0) return static_cast<std::size_t>(std::min<unsigned long long>(v, SIZE_MAX));
  }
  return std::numeric_limits<std::size_t>::max();
}

std::size_t default_limit() {
  std::size_t limit = std::numeric_limits<std::size_t>::max();
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) limit = std::size_t(pages) * std::size_t(page);
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit r {};
    if (::getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
      limit = std::min<std::size_t>(limit, static_cast<std::size_t>(r.rlim_cur));
  }
  return std::min(limit, cgroup_limit());
}

// The registry of temporary files: fixed slots a signal handler can walk without locks.
// A slot is free (0), being filled (1) or holds a path (2).
constexpr int temporary_slots = 64;
struct TemporarySlot {
  std::atomic<int> state{0};
  char path[4096] = {};
};
TemporarySlot temporaries[temporary_slots];

}  // namespace

std::size_t memory_limit() {
  const std::size_t chosen = chosen_limit.load();
  if (chosen > 0) return chosen;
  static const std::size_t computed = default_limit();
  return computed;
}

void set_memory_limit(std::size_t bytes) {
  chosen_limit = bytes;
}

std::size_t max_input_bytes() {
  return memory_limit() / 4;
}

std::string format_bytes(double bytes) {
  static const char* const units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000 && u < 6) bytes /= 1000, ++u;
  char b[48];
  std::snprintf(b, sizeof b, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return b;
}

void remove_temporary_files() noexcept {
  for (TemporarySlot& slot : temporaries)
    if (slot.state.load() == 2) ::unlink(slot.path);
}

namespace detail {

int register_temporary(const std::string& path) {
  if (path.size() >= sizeof(TemporarySlot::path)) return -1;
  for (int k = 0; k < temporary_slots; ++k) {
    int free = 0;
    if (!temporaries[k].state.compare_exchange_strong(free, 1)) continue;
    std::memcpy(temporaries[k].path, path.c_str(), path.size() + 1);
    temporaries[k].state = 2;
    return k;
  }
  return -1;  // more than 64 outputs at once: the later ones are not removed on a signal
}

void unregister_temporary(int slot) {
  if (slot >= 0 && slot < temporary_slots) temporaries[slot].state = 0;
}

void refuse_size(const std::string& what, std::size_t limit) {
  throw Error(what + " is larger than " + format_bytes(double(limit)) + ", the most an input may take with " +
              "the memory limit of " + format_bytes(double(memory_limit())) +
              " (the tools' --max-memory raises it)");
}

HeldBytes::HeldBytes(std::size_t limit, std::string what) : limit_(limit), what_(std::move(what)) {}

void HeldBytes::add(std::size_t bytes) {
  const std::size_t now = held_ += bytes;
  if (now > limit_)
    throw Error(what_ + " (over " + format_bytes(double(limit_)) + ", half the memory limit " +
                format_bytes(double(memory_limit())) + "; the tools' --max-memory raises it)");
}

}  // namespace detail

}  // namespace section
