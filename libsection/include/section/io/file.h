// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file io/file.h
/// Whole files in and out ("-" = standard input or output).
#include <string>

namespace section {

/// Reads a whole file ("-" = standard input) into memory; throws section::Error naming
/// the file when it cannot be opened or read.
std::string read_file(const std::string& path);

/// Writes `bytes` to `path` ("-" = standard output); throws section::Error on failure.
void write_file(const std::string& path, const std::string& bytes);

}  // namespace section
