// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The input formats in one place: their extensions, how their content is told apart, their
// readers. A new input format is one entry in input_formats() (formats.cpp) plus its reader.
#include "io/byte_source.h"
#include "section/io/cloud_io.h"
#include "section/mesh.h"

#include <string>
#include <string_view>
#include <vector>

namespace section::detail {

/// Reads the points of a cloud from `src`: `checked` receives them checked against
/// max_coordinate, `raw` unchecked (for a reader that checks while it reads). Returns the
/// number of points.
using CloudReader = std::size_t (*)(ByteSource& src, const CloudReadOptions& options,
                                    const PointChunkFn& checked, const PointChunkFn& raw);
/// Reads a mesh from the whole content `text` of the file `path`.
using MeshReader = Mesh (*)(const std::string& path, const std::string& text);

/// An input format.
struct InputFormat {
  std::vector<std::string_view> extensions;    ///< lower case, without the dot; named in messages
  std::vector<std::string_view> also;          ///< further extensions, read but not named in messages
  CloudFormat cloud = CloudFormat::automatic;  ///< its name for CloudReadOptions; automatic: no clouds
  CloudReader read_cloud = nullptr;            ///< nullptr when it holds no clouds
  bool text = false;  ///< a text format: its encoding is checked and a UTF-8 BOM skipped
  const char* magic =
      nullptr;  ///< how its content starts (prefixes separated by '|'), for input with no extension (stdin)
  MeshReader read_mesh = nullptr;  ///< nullptr when it holds no meshes
  /// For a format of clouds and meshes: true when the file holds a mesh.
  bool (*holds_mesh)(ByteSource& src) = nullptr;
};

/// Every input format, in the order their extensions are named in messages.
const std::vector<InputFormat>& input_formats();

/// The extension of `path` in lower case, without the dot; "" when it has none (a dot in a
/// directory's name does not count).
std::string extension(const std::string& path);

/// The format of a file by its extension, or nullptr.
const InputFormat* format_of_extension(const std::string& path);

/// The mesh format of an input with no extension (standard input, a process substitution)
/// by its first bytes `head` and its size: PLY (by its magic; a mesh when its header
/// declares faces, told by the caller), STL (binary: 84 + 50 x its count bytes; ascii:
/// `solid` then `facet`), OFF (its keyword) or OBJ (its first statement); nullptr for
/// anything else (a cloud).
const InputFormat* mesh_format_of_content(std::string_view head, long long size);

/// The format of a cloud: `forced` unless automatic, else by `path`'s extension, else (standard
/// input, no extension) by its first bytes `head`, else XYZ. Throws section::Error for a mesh
/// or an unknown extension.
const InputFormat& cloud_format(const std::string& path, std::string_view head, CloudFormat forced);

/// ".ext .ext ..." of the formats that hold meshes (`meshes`) or clouds, for messages.
std::string named_extensions(bool meshes);

}  // namespace section::detail
