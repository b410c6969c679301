#pragma once
// PLY scalar type names, shared by the cloud and mesh readers.
#include <string_view>

namespace section::detail {

/// Size in bytes and kind ('i' signed, 'u' unsigned, 'f' floating) of a PLY scalar type
/// name (both the classic and the sized spellings); false for an unknown name.
inline bool ply_type(std::string_view t, int& size, char& kind) {
  static const struct { const char* name; int size; char kind; } types[] = {
      {"char", 1, 'i'},  {"int8", 1, 'i'},    {"uchar", 1, 'u'},  {"uint8", 1, 'u'},
      {"short", 2, 'i'}, {"int16", 2, 'i'},   {"ushort", 2, 'u'}, {"uint16", 2, 'u'},
      {"int", 4, 'i'},   {"int32", 4, 'i'},   {"uint", 4, 'u'},   {"uint32", 4, 'u'},
      {"float", 4, 'f'}, {"float32", 4, 'f'}, {"double", 8, 'f'}, {"float64", 8, 'f'}};
  for (const auto& e : types)
    if (t == e.name) {
      size = e.size;
      kind = e.kind;
      return true;
    }
  return false;
}

}  // namespace section::detail
