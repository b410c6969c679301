// SPDX-License-Identifier: GPL-3.0-or-later
// PartReader: a stream read part by part as it comes, for the part scheduler (run_stage).
#include "section/io/stream_reader.h"

#include "io/byte_source.h"
#include "io/stream_text.h"
#include "io/text.h"
#include "section/error.h"
#include "section/io/limits.h"

#include <cstring>

namespace section {

namespace {

// The key of a `# key ...` line ("part", "end", "table", ...), or "" for any other line.
std::string_view key_of(std::string_view line) {
  return line.empty() || line[0] != '#' ? std::string_view{} : detail::meta_line(line).key;
}

bool blank(std::string_view line) {
  return line.find_first_not_of(" \t\r\n") == std::string_view::npos;
}

}  // namespace

Stream parse_stream_part(const StreamPart& part, const std::string& source, int threads) {
  return detail::parse_stream_text(*part.text, source, part.text,
                                   detail::PartText{true, part.first_line, threads});
}

PartReader::PartReader(const std::string& path) : in_(std::make_unique<detail::ByteSource>(path, "")) {
  source_ = in_->name();
  // Binary data, UTF-16 or CR-only line ends are told at once, not after a line of
  // max_text_line bytes (an endless /dev/zero): from the first 64 KiB, or the first line
  // when it comes sooner (a pipe's writer may write a part, then take its time).
  constexpr std::size_t first_bytes = 1 << 16;
  while (in_->bytes().size() < first_bytes && in_->bytes().find('\n') == std::string_view::npos &&
         in_->fetch(first_bytes - in_->bytes().size(), true) > 0) {
  }
  if (const char* why = detail::text_encoding_problem(in_->bytes()))
    throw Error("pipe: " + source_ + ": " + why);
  // The preamble: the lines before the first `# part`, `# table` or data line.
  std::string_view line;
  while (next_line(line)) {
    const std::string_view key = key_of(line);
    if (key == "part" || key == "table" || (!blank(line) && line[0] != '#')) {
      text_ = std::string(line);
      break;
    }
    head_ += line;
    held(head_, "its preamble");
  }
  parted_ = key_of(text_) == "part";
  if (parted_) label_ = std::string(detail::meta_line(text_).rest);
  if (parted_) labels_.insert(label_);
  first_line_ = line_no_;
}

PartReader::~PartReader() = default;

bool PartReader::next_line(std::string_view& line) {
  if (!in_->next_line(line, max_text_line)) return false;
  ++line_no_;
  if (line.size() >= max_text_line && line.back() != '\n')
    detail::stream_fail(source_, line_no_, "line longer than " + format_bytes(double(max_text_line)));
  return true;
}

void PartReader::take_rows() {
  // The whole lines at hand, cut before the first line that starts with '#' (a '#' may also
  // stand inside a row: those are passed over).
  const std::string_view at = in_->bytes();
  if (at.empty() || at[0] == '#') return;
  const std::size_t whole = at.rfind('\n') + 1;  // 0 when no line is whole
  std::size_t taken = whole;
  for (std::size_t from = 0; from < whole;) {
    const void* hash = std::memchr(at.data() + from, '#', whole - from);
    if (!hash) break;
    const std::size_t k = std::size_t(static_cast<const char*>(hash) - at.data());
    if (at[k - 1] == '\n') {
      taken = k;
      break;
    }
    from = k + 1;
  }
  if (!taken) return;
  text_.append(at.data(), taken);
  in_->consume(taken);
  line_no_ += detail::count_lines(at.substr(0, taken));
  held(text_, "part " + label_);
}

void PartReader::held(const std::string& text, const std::string& what) const {
  if (text.size() > max_input_bytes())
    detail::refuse_size("pipe: " + source_ + ": " + what, max_input_bytes());
}

Stream PartReader::preamble() const {
  Stream head = parse_stream(head_, source_);
  if (!head.issues.empty()) throw Error("pipe: " + source_ + ": issues before the first '# part'");
  return head;
}

std::string PartReader::whole() {
  std::string text = std::move(head_);
  text += text_;
  text += in_->read_all();
  held(text, "the stream");
  return text;
}

bool PartReader::next(StreamPart& part) {
  if (end_error_line_) detail::stream_fail(source_, end_error_line_, "'# end' takes nothing after it");
  std::string_view line;
  if (ended_) {
    while (next_line(line))
      if (!blank(line)) detail::stream_fail(source_, line_no_, "a line after '# end'");
    return false;
  }
  while (take_rows(), next_line(line)) {
    const std::string_view key = key_of(line);
    if (key == "part" || key == "end") {
      part = StreamPart{label_, std::make_shared<const std::string>(std::move(text_)), first_line_};
      text_.clear();
      if (key == "part") text_.reserve(part.text->size() + part.text->size() / 8);  // the next is alike
      first_line_ = line_no_;
      label_ = std::string(detail::meta_line(line).rest);
      if (key == "part" && !labels_.insert(label_).second)
        detail::stream_fail(source_, line_no_,
                            "a second part of section " + label_ + " (each section is one part)");
      if (key == "part") text_ += line;
      ended_ = key == "end";
      if (ended_ && !label_.empty()) end_error_line_ = line_no_;  // reported once this part is staged
      return true;
    }
    text_ += line;
    held(text_, "part " + label_);
  }
  throw detail::truncated_parts(source_);
}

}  // namespace section
