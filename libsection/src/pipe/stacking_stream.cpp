// SPDX-License-Identifier: GPL-3.0-or-later
// The stacking stage on the stream (stacking_stream.h).
#include "section/pipe/stacking_stream.h"

#include "section/error.h"
#include "section/pipe/schema.h"
#include "pipe/adapter.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <string>

namespace section {

std::string stack_flags_text(std::uint32_t flags) {
  std::string out;
  for (const auto& c : stack_check_names)
    if (flags & static_cast<std::uint32_t>(c.check))
      out += std::string(out.empty() ? "its values fail blade checks " : ", ") + c.name + " (" + c.why +
             ": " + c.columns + ")";
  return out;
}

std::vector<StackedSection> stacked_sections(const Stream& stream) {
  const Table& t = schema::params.get(stream);
  std::map<int, Frame> frame_of;
  if (schema::frames.find(stream)) frame_of = frames(stream);
  const auto c = [&](const char* name) { return t.column(name); };
  const std::size_t id = c("section"), cu = c("centroid_u"), cv = c("centroid_v"), lu = c("le_u"),
                    lv = c("le_v"), tu = c("te_u"), tv = c("te_v"), stagger = c("stagger"),
                    chord = c("chord"), thick = c("max_thickness"), flags = c("flags");
  std::vector<StackedSection> out;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    StackedSection s;
    s.id = static_cast<int>(t.at(r, id));
    if (!frame_of.empty()) {
      const auto f = frame_of.find(s.id);
      if (f == frame_of.end())
        throw Error("blade: section " + std::to_string(s.id) + " has params but no frame (table frames)");
      s.frame = f->second;
    }
    s.params.centroid = {t.at(r, cu), t.at(r, cv)};
    s.params.le_point = {t.at(r, lu), t.at(r, lv)};
    s.params.te_point = {t.at(r, tu), t.at(r, tv)};
    s.params.stagger = t.at(r, stagger);
    s.params.chord = t.at(r, chord);
    s.params.max_thickness = t.at(r, thick);
    s.flags = flags_mask(t.at(r, flags));
    out.push_back(s);
  }
  return out;
}

StackingResult stacking_stream(Stream& stream, const StackingOptions& options) {
  convert_to_mm(stream);
  pipe::restage(stream, "blade");
  // A section whose values are not all finite is left out with an issue; the others go on.
  std::vector<StackedSection> sections;
  for (const StackedSection& s : stacked_sections(stream)) {
    const SectionParams& p = s.params;
    if (p.centroid.allFinite() && p.le_point.allFinite() && p.te_point.allFinite() &&
        std::isfinite(p.stagger) && std::isfinite(p.chord) && std::isfinite(p.max_thickness))
      sections.push_back(s);
    else
      stream.issues.push_back(
          {s.id, 0, "blade", "its params hold a value that is not finite: left out of the blade"});
  }
  const StackingResult r = stacking(sections, options);
  Table blade = schema::blade.table();
  for (const StackedValues& v : r.sections) {
    schema::blade.add(blade, {v.id, v});
    if (v.flags) stream.issues.push_back({v.id, 0, "blade", stack_flags_text(v.flags)});
    if (v.reference && (v.flags & static_cast<std::uint32_t>(StackCheck::twist)))
      stream.issues.push_back(
          {v.id, 0, "blade",
           "the reference section's stagger is flagged, and so every twist: --reference N "
           "measures the twist from another section"});
  }
  Table line = schema::stacking.table();
  for (std::size_t k = 0; k < r.samples.size(); ++k) schema::stacking.add(line, {k, r.samples[k]});
  stream.put(std::move(blade));
  stream.put(std::move(line));
  return r;
}

}  // namespace section
