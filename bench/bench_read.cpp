// SPDX-License-Identifier: GPL-3.0-or-later
// bench_read [--threads N] FILE...: reads each cloud with the library's chunked reader and
// prints the point count, wall time and throughput (points per second). --threads sets the
// text parser's worker threads (0 = all cores, the default).
#include "section/cloud.h"
#include "section/io/cloud_io.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <exception>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_read [--threads N] FILE...\n");
    return 2;
  }
  try {
    section::CloudReadOptions options;
    for (int i = 1; i < argc; ++i) {
      if (std::string(argv[i]) == "--threads" && i + 1 < argc) {
        options.threads = std::atoi(argv[++i]);
        continue;
      }
      const auto t0 = std::chrono::steady_clock::now();
      double checksum = 0;
      const std::size_t n = section::read_cloud_chunks(
          argv[i],
          [&](const Eigen::Vector3d* p, std::size_t count) {
            for (std::size_t k = 0; k < count; ++k) checksum += p[k].z();
          },
          options);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("%s: %zu points in %.3f s = %.1f million points/s (checksum %.6g)\n", argv[i], n, s,
                  n / s / 1e6, checksum);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_read: error: %s\n", e.what());
    return 1;
  }
}
