// SPDX-License-Identifier: GPL-3.0-or-later
// The XML section of an E57 file (ASTM E2807, section 8): parsed with tinyxml2 (Debian's
// libtinyxml2-dev), then read for what the points need. Each child of /data3D is a scan:
// its pose (a unit quaternion rotation w, x, y, z and a translation, both optional: the
// identity), and its points, a CompressedVector with the physical offset of its binary
// section (fileOffset), its record count and a prototype whose leaves are the fields of a
// record. Numbers are parsed with from_chars (no locale).
#include "io/cloud_e57.h"

#include "io/text.h"
#include "section/error.h"

#include <Eigen/Geometry>
#include <tinyxml2.h>

#include <cmath>
#include <limits>

namespace section::detail {

namespace {

using tinyxml2::XMLElement;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw Error("read_cloud: " + name + ": E57 " + what);
}

std::string attribute(const XMLElement* e, const char* key) {
  const char* v = e->Attribute(key);
  return v ? std::string(trim(v)) : std::string();
}

std::string type_of(const XMLElement* e) {
  return attribute(e, "type");
}

// A numeric attribute (or `def` when it is absent), checked.
template <class T>
T number_attribute(const XMLElement* e, const char* key, T def, const std::string& where) {
  const std::string s = attribute(e, key);
  if (s.empty()) return def;
  T v{};
  bool ok = false;
  if constexpr (std::is_floating_point_v<T>)
    ok = parse_double(s, v) && std::isfinite(v);
  else
    ok = parse_integer(s, v);
  if (!ok) throw Error(where + ": " + key + "=" + quoted(s) + " is not a number");
  return v;
}

// The value of a Float, Integer or ScaledInteger element `child` of `parent`; `def` when it
// is absent (an element without text is 0, as E2807 says).
double number_child(const XMLElement* parent, const char* child, double def, const std::string& where) {
  const XMLElement* e = parent ? parent->FirstChildElement(child) : nullptr;
  if (!e) return def;
  const std::string type = type_of(e);
  const std::string at = where + "/" + child;
  if (type != "Float" && type != "Integer" && type != "ScaledInteger")
    throw Error(at + " is of type " + quoted(type) + ", not a number");
  const char* text = e->GetText();
  double v = 0;
  if (text && !trim(text).empty() && !(parse_double(trim(text), v) && std::isfinite(v)))
    throw Error(at + ": " + quoted(text) + " is not a number");
  if (type == "ScaledInteger")
    v = v * number_attribute(e, "scale", 1.0, at) + number_attribute(e, "offset", 0.0, at);
  return v;
}

// A prototype leaf as a field; throws for what is not a number.
E57Field field_of(const XMLElement* e, const std::string& path, const std::string& where) {
  E57Field f;
  f.name = path;
  const std::string type = type_of(e);
  const std::string at = where + ": its points' field " + quoted(path);
  if (type == "Float") {
    const std::string precision = attribute(e, "precision");
    if (precision != "" && precision != "single" && precision != "double")
      throw Error(at + " has precision " + quoted(precision) + " (single or double are)");
    f.single = precision == "single";
    return f;
  }
  if (type != "Integer" && type != "ScaledInteger")
    throw Error(at + " is of type " + quoted(type) +
                ": only Float, Integer and ScaledInteger fields are read");
  f.kind = type == "Integer" ? 'i' : 's';
  f.minimum = number_attribute(e, "minimum", std::numeric_limits<std::int64_t>::min(), at);
  f.maximum = number_attribute(e, "maximum", std::numeric_limits<std::int64_t>::max(), at);
  if (f.maximum < f.minimum) throw Error(at + " has its maximum below its minimum");
  if (f.kind == 's') {
    f.scale = number_attribute(e, "scale", 1.0, at);
    f.offset = number_attribute(e, "offset", 0.0, at);
    if (f.scale == 0) throw Error(at + " has scale 0");
  }
  const std::uint64_t range = static_cast<std::uint64_t>(f.maximum) - static_cast<std::uint64_t>(f.minimum);
  while (f.bits < 64 && (range >> f.bits) != 0) ++f.bits;
  return f;
}

// The leaves of a prototype, depth first: the order of a data packet's bytestreams.
void leaves(const XMLElement* e, const std::string& prefix, std::vector<E57Field>& out,
            const std::string& where) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string path = prefix + c->Name();
    if (type_of(c) == "Structure")
      leaves(c, path + "/", out, where);
    else
      out.push_back(field_of(c, path, where));
  }
}

// The codecs vector may only name bitPackCodec (the one codec E2807 defines).
void check_codecs(const XMLElement* points, const std::string& where) {
  const XMLElement* codecs = points->FirstChildElement("codecs");
  if (!codecs) return;
  for (const XMLElement* c = codecs->FirstChildElement(); c; c = c->NextSiblingElement())
    for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement())
      if (std::string(k->Name()) != "inputs" && std::string(k->Name()) != "bitPackCodec")
        throw Error(where + ": its points use the codec " + quoted(k->Name()) +
                    ", which is not supported (only bitPackCodec is)");
}

void read_pose(const XMLElement* scan, E57Scan& s, const std::string& where) {
  const XMLElement* pose = scan->FirstChildElement("pose");
  if (!pose) return;
  const XMLElement* r = pose->FirstChildElement("rotation");
  const XMLElement* t = pose->FirstChildElement("translation");
  const std::string rw = where + "/pose/rotation", tw = where + "/pose/translation";
  Eigen::Quaterniond q(number_child(r, "w", r ? 0 : 1, rw), number_child(r, "x", 0, rw),
                       number_child(r, "y", 0, rw), number_child(r, "z", 0, rw));
  if (!(q.norm() > 1e-9)) throw Error(rw + " is not a rotation (a quaternion of length 0)");
  s.rotation = q.normalized().toRotationMatrix();
  s.translation = {number_child(t, "x", 0, tw), number_child(t, "y", 0, tw), number_child(t, "z", 0, tw)};
  s.posed = !(q.w() == 1 && q.vec().isZero()) || !s.translation.isZero();
}

// Which fields hold the coordinates and the invalid state.
void locate_coordinates(E57Scan& s, const std::string& where) {
  const auto find = [&](const char* n) {
    for (std::size_t i = 0; i < s.fields.size(); ++i)
      if (s.fields[i].name == n) return static_cast<int>(i);
    return -1;
  };
  const int c[3] = {find("cartesianX"), find("cartesianY"), find("cartesianZ")};
  const int p[3] = {find("sphericalRange"), find("sphericalAzimuth"), find("sphericalElevation")};
  if (c[0] >= 0 && c[1] >= 0 && c[2] >= 0) {
    std::copy(c, c + 3, s.coord);
    s.invalid = find("cartesianInvalidState");
  } else if (p[0] >= 0 && p[1] >= 0 && p[2] >= 0) {
    std::copy(p, p + 3, s.coord);
    s.invalid = find("sphericalInvalidState");
    s.spherical = true;
  } else {
    throw Error(where +
                ": its points have neither cartesianX, Y and Z nor sphericalRange, Azimuth and Elevation");
  }
}

E57Scan read_scan(const XMLElement* scan, std::size_t index, const std::string& name) {
  E57Scan s;
  const XMLElement* title = scan->FirstChildElement("name");
  s.label = "scan " + std::to_string(index + 1);
  if (title && title->GetText()) s.label += " (" + quoted(title->GetText()) + ")";
  const std::string where = "read_cloud: " + name + ": E57 " + s.label;
  read_pose(scan, s, where);
  const XMLElement* points = scan->FirstChildElement("points");
  if (!points || type_of(points) != "CompressedVector")
    throw Error(where + " has no points (a CompressedVector)");
  s.offset = number_attribute<std::uint64_t>(points, "fileOffset", 0, where + "/points");
  s.records = number_attribute<std::uint64_t>(points, "recordCount", 0, where + "/points");
  const XMLElement* prototype = points->FirstChildElement("prototype");
  if (!prototype) throw Error(where + ": its points have no prototype");
  leaves(prototype, "", s.fields, where);
  check_codecs(points, where);
  locate_coordinates(s, where);
  return s;
}

}  // namespace

std::vector<E57Scan> e57_scans(std::string_view xml, const std::string& name) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
    fail(name, "XML section does not parse (line " + std::to_string(doc.ErrorLineNum()) +
                   " of the XML: " + std::string(doc.ErrorName()) + ")");
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "e57Root") fail(name, "XML section has no e57Root element");
  const XMLElement* data3d = root->FirstChildElement("data3D");
  std::vector<E57Scan> scans;
  for (const XMLElement* c = data3d ? data3d->FirstChildElement() : nullptr; c; c = c->NextSiblingElement())
    scans.push_back(read_scan(c, scans.size(), name));
  if (scans.empty()) fail(name, "file holds no scans (its data3D is empty or absent)");
  return scans;
}

}  // namespace section::detail
