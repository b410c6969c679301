// PartReader: a stream read part by part as it comes, for the part scheduler (run_stage).
#include "section/io/stream_reader.h"

#include "io/byte_source.h"
#include "io/stream_text.h"
#include "section/error.h"

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

Stream parse_stream_part(const StreamPart& part, const std::string& source) {
  return detail::parse_stream_text(*part.text, source, part.text, detail::PartText{true, part.first_line});
}

PartReader::PartReader(const std::string& path) : in_(std::make_unique<detail::ByteSource>(path, "")) {
  source_ = in_->name();
  // The preamble: the lines before the first `# part`, `# table` or data line.
  std::string_view line;
  while (in_->next_line(line)) {
    ++line_no_;
    const std::string_view key = key_of(line);
    if (key == "part" || key == "table" || (!blank(line) && line[0] != '#')) {
      text_ = std::string(line);
      break;
    }
    head_ += line;
  }
  parted_ = key_of(text_) == "part";
  if (parted_) label_ = std::string(detail::meta_line(text_).rest);
  first_line_ = line_no_;
}

PartReader::~PartReader() = default;

Stream PartReader::preamble() const {
  Stream head = parse_stream(head_, source_);
  if (!head.issues.empty()) throw Error("pipe: " + source_ + ": issues before the first '# part'");
  return head;
}

std::string PartReader::whole() {
  std::string text = std::move(head_);
  text += text_;
  text += in_->read_all();
  return text;
}

bool PartReader::next(StreamPart& part) {
  if (end_error_line_) detail::stream_fail(source_, end_error_line_, "'# end' takes nothing after it");
  std::string_view line;
  if (ended_) {
    while (in_->next_line(line)) {
      ++line_no_;
      if (!blank(line)) detail::stream_fail(source_, line_no_, "a line after '# end'");
    }
    return false;
  }
  while (in_->next_line(line)) {
    ++line_no_;
    const std::string_view key = key_of(line);
    if (key == "part" || key == "end") {
      part = StreamPart{label_, std::make_shared<const std::string>(std::move(text_)), first_line_};
      text_.clear();
      first_line_ = line_no_;
      label_ = std::string(detail::meta_line(line).rest);
      if (key == "part") text_ += line;
      ended_ = key == "end";
      if (ended_ && !label_.empty()) end_error_line_ = line_no_;  // reported once this part is staged
      return true;
    }
    text_ += line;
  }
  throw detail::truncated_parts(source_);
}

}  // namespace section
