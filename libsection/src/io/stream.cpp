// SPDX-License-Identifier: GPL-3.0-or-later
// The stream model: tables and their lookups, and the small pieces of its text form.
#include "section/io/stream.h"

#include "io/stream_text.h"
#include "io/text.h"
#include "section/error.h"

#include <algorithm>
#include <charconv>

namespace section {

std::size_t Table::column(const std::string& column_name) const {
  const long c = find_column(column_name);
  if (c < 0) throw Error("pipe: table '" + name + "' has no column '" + column_name + "'");
  return static_cast<std::size_t>(c);
}

long Table::find_column(const std::string& column_name) const {
  const auto it = std::find(columns.begin(), columns.end(), column_name);
  return it == columns.end() ? -1 : static_cast<long>(it - columns.begin());
}

namespace {

template <class Row>
void append_row(Table& t, const Row& row) {
  if (row.size() != t.columns.size())
    throw Error("pipe: a row of table '" + t.name + "' has " + std::to_string(row.size()) + " values for " +
                std::to_string(t.columns.size()) + " columns");
  t.values.insert(t.values.end(), row.begin(), row.end());
}

}  // namespace

void Table::add_row(std::initializer_list<double> row) {
  append_row(*this, row);
}

void Table::add_row(const std::vector<double>& row) {
  append_row(*this, row);
}

const Table* Stream::find(const std::string& name) const {
  for (const auto& t : tables)
    if (t.name == name) return &t;
  return nullptr;
}

Table* Stream::find(const std::string& name) {
  return const_cast<Table*>(static_cast<const Stream*>(this)->find(name));
}

const Table& Stream::get(const std::string& name, const std::string& produced_by) const {
  if (const Table* t = find(name)) return *t;
  throw Error("pipe: the stream has no '" + name + "' table (it is written by " + produced_by + ")");
}

void Stream::put(Table table) {
  if (Table* t = find(table.name))
    *t = std::move(table);
  else
    tables.push_back(std::move(table));
}

void Stream::erase(const std::string& name) {
  tables.erase(std::remove_if(tables.begin(), tables.end(), [&](const Table& t) { return t.name == name; }),
               tables.end());
}

bool Stream::failed(int section, int loop) const {
  return std::any_of(issues.begin(), issues.end(), [&](const SectionIssue& i) {
    return i.section == section && (i.loop == -1 || loop == -1 || i.loop == loop);
  });
}

void append_rows(Table& to, const Table& from) {
  if (to.columns.empty() && to.values.empty()) {
    to.name = from.name;
    to.columns = from.columns;
  } else if (to.columns != from.columns) {
    throw Error("pipe: table '" + from.name + "' has other columns than before");
  }
  // A partial row would shift every row appended after it.
  if (const std::string why = detail::partial_rows(from); !why.empty())
    throw Error("pipe: table '" + from.name + "': " + why + ", to append");
  to.values.insert(to.values.end(), from.values.begin(), from.values.end());
}

std::string format_number(double value) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

namespace detail {

void stream_fail(const std::string& source, std::size_t line, const std::string& what) {
  throw Error("pipe: " + source + ":" + std::to_string(line) + ": " + what);
}

MetaLine meta_line(std::string_view line) {
  std::string_view body = trim(line.substr(1));
  while (!body.empty() && (body.back() == '\n' || body.back() == '\r')) body.remove_suffix(1);
  const std::size_t space = body.find(' ');
  return {body.substr(0, space),
          space == std::string_view::npos ? std::string_view{} : trim(body.substr(space)), body};
}

Error truncated_parts(const std::string& source) {
  return Error("pipe: " + source +
               ": the stream is split into parts but lacks its closing '# end' line (truncated "
               "stream, or the tool that wrote it failed)");
}

std::string partial_rows(const Table& t) {
  const std::size_t cols = t.columns.size();
  if (cols == 0 ? t.values.empty() : t.values.size() % cols == 0) return {};
  return "its " + std::to_string(t.values.size()) + " values are not whole rows of its " +
         std::to_string(cols) + " columns";
}

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

}  // namespace detail

}  // namespace section
