// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/limits.h
/// The readers' resource policy (docs/ROBUSTNESS.md, "Resource policy"): how much of an
/// input is held in memory, scaled to the memory the process may use, and the temporary
/// files of the outputs being written.
#include <cstddef>
#include <string>

namespace section {

/// Bytes of memory this process may use: set_memory_limit's value when set, else the least
/// of the physical memory, `ulimit -v` (RLIMIT_AS), RLIMIT_DATA and the cgroup's memory limit.
std::size_t memory_limit();

/// Sets memory_limit() for the whole process, like a ulimit (the tools' --max-memory);
/// 0 goes back to the default.
void set_memory_limit(std::size_t bytes);

/// The most bytes of one input held in memory: a stream (or one part of it), a mesh, a
/// planes file, a profile; and of a cloud from a pipe spooled to a temporary file (4x this).
/// A quarter of memory_limit(): text takes three to four times its size once parsed.
std::size_t max_input_bytes();

/// The longest line of a stream or a plain CSV file (16 MiB; a cloud's: 64 KiB).
constexpr std::size_t max_text_line = std::size_t(16) << 20;

/// `bytes` for a message: "512 bytes", "1.5 MB", "23.4 GB".
std::string format_bytes(double bytes);

/// Removes the temporary files of the outputs being written (each output is written under
/// a temporary name and renamed when whole). Async-signal-safe: for a SIGINT or SIGTERM
/// handler (the tools install one).
void remove_temporary_files() noexcept;

}  // namespace section
