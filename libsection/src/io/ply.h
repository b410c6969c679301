// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The PLY header and its binary scalars, decoded once for the cloud and the mesh readers.
#include "io/byte_source.h"

#include <cstddef>
#include <string>
#include <vector>

namespace section::detail {

enum class PlyFormat { ascii, binary_le, binary_be };

struct PlyProperty {
  std::string name;
  int size = 0;        ///< bytes of a scalar (of a list's items)
  char kind = 'f';     ///< 'f' floating, 'i' signed, 'u' unsigned
  int count_size = 0;  ///< bytes of a list's count; 0 for a scalar
  char count_kind = 'u';
  std::string count_type;  ///< a list's count type as written
  std::size_t line = 0;    ///< the header line declaring it
  bool list() const { return count_size != 0; }
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> props;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t bytes = 0;  ///< the header's length, up to and with the end_header line
  std::size_t lines = 0;  ///< its lines
  /// The binary scalars are in the other byte order than the host's.
  bool swap() const;
};

/// How a reader's messages place a header error: after `component` and the file's name,
/// "NAME:LINE: what" (the cloud reader) or "NAME: line LINE: what" (the mesh readers).
struct PlyMessages {
  std::string component;    ///< e.g. "read_cloud: "
  bool line_words = false;  ///< "line N: " rather than ":N: "
};

/// Decodes the header at the start of `src.bytes()` (fetching more as needed, consuming
/// nothing): `ply`, then `format`, `element NAME COUNT`, `property TYPE NAME` and
/// `property list COUNT_TYPE TYPE NAME` lines (comment and obj_info lines skipped) up to
/// `end_header`. Throws section::Error naming the line of anything else.
PlyHeader read_ply_header(ByteSource& src, const PlyMessages& messages);

/// True when the header at the start of `src` declares faces (`element face N`, N > 0);
/// nothing else of it is checked (the mesh reader words what is wrong). Never throws.
bool ply_declares_faces(ByteSource& src);

/// The binary scalar of `size` bytes and `kind` at `p`, byte-swapped when `swap`.
double ply_scalar(const unsigned char* p, int size, char kind, bool swap);

}  // namespace section::detail
