// SPDX-License-Identifier: GPL-3.0-or-later
// Stream tables as JSON, grouped by section.
#include "section/io/json.h"

#include "io/text.h"
#include "section/error.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace section {

namespace {

std::string json_string(const std::string& text) {
  const std::string s = detail::well_formed_utf8(text);  // JSON is UTF-8: a stray byte made it unreadable
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

std::string json_number(double v) {
  return std::isfinite(v) ? format_number(v) : "null";
}

// A row's cells as an object, the section column left out.
std::string row_object(const Table& t, std::size_t r, std::size_t skip) {
  std::string out = "{";
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    if (c == skip) continue;
    if (out.size() > 1) out += ", ";
    out += json_string(t.columns[c]) + ": " + json_number(t.at(r, c));
  }
  return out + "}";
}

// One table's rows of one section (`rows`), in the form its columns call for.
std::string table_value(const Table& t, const std::vector<std::size_t>& rows, std::size_t cs, int section) {
  if (t.find_column("index") >= 0) {
    std::string out = "{";
    for (std::size_t c = 0; c < t.columns.size(); ++c) {
      if (c == cs) continue;
      out += std::string(out.size() > 1 ? ", " : "") + json_string(t.columns[c]) + ": [";
      for (std::size_t i = 0; i < rows.size(); ++i) out += (i ? ", " : "") + json_number(t.at(rows[i], c));
      out += "]";
    }
    return out + "}";
  }
  // Rows keyed by more than the section: a loop (splines), a zone or a compared value (compare).
  if (t.find_column("loop") >= 0 || t.find_column("zone") >= 0 || t.find_column("item") >= 0) {
    std::string out = "[";
    for (std::size_t i = 0; i < rows.size(); ++i) out += (i ? ", " : "") + row_object(t, rows[i], cs);
    return out + "]";
  }
  if (rows.size() > 1)
    throw Error("json: table '" + t.name + "' has " + std::to_string(rows.size()) + " rows for section " +
                std::to_string(section) + ", one was expected");
  return row_object(t, rows.front(), cs);
}

std::string issues(const Stream& stream) {
  std::string out = "[";
  for (const auto& i : stream.issues)
    out += std::string(out.size() > 1 ? ",\n    " : "\n    ") + "{\"section\": " + std::to_string(i.section) +
           ", \"loop\": " + std::to_string(i.loop) + ", \"stage\": " + json_string(i.stage) +
           ", \"message\": " + json_string(i.message) + "}";
  return out + (stream.issues.empty() ? "]" : "\n  ]");
}

}  // namespace

std::string format_json(const Stream& stream, const std::vector<const Table*>& tables) {
  // rows[table][section]: the table's rows of that section, in order.
  std::vector<std::map<int, std::vector<std::size_t>>> rows(tables.size());
  std::vector<std::size_t> section_column(tables.size());
  std::set<int> sections;
  for (std::size_t k = 0; k < tables.size(); ++k) {
    if (!tables[k]) throw Error("json: a table to write is missing (a null pointer)");
    const Table& t = *tables[k];
    if (t.find_column("section") < 0) throw Error("json: table '" + t.name + "' has no 'section' column");
    section_column[k] = t.column("section");
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const int s = detail::section_id(t.at(r, section_column[k]), t.name, r);
      rows[k][s].push_back(r);
      sections.insert(s);
    }
  }
  std::string out =
      "{\n  \"libsection\": 1,\n  \"units\": " + json_string(stream.units) + ",\n  \"history\": [";
  for (std::size_t i = 0; i < stream.history.size(); ++i)
    out += (i ? ", " : "") + json_string(stream.history[i]);
  out += "],\n  \"issues\": " + issues(stream) + ",\n  \"sections\": [";
  bool first = true;
  for (int s : sections) {
    out += std::string(first ? "\n" : ",\n") + "    {\"section\": " + std::to_string(s);
    first = false;
    for (std::size_t k = 0; k < tables.size(); ++k) {
      const auto it = rows[k].find(s);
      if (it == rows[k].end()) continue;
      out += ",\n     " + json_string(tables[k]->name) + ": " +
             table_value(*tables[k], it->second, section_column[k], s);
    }
    out += "}";
  }
  return out + (sections.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

}  // namespace section
