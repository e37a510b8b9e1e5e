// File → parse (simdjson, RapidJSON where simdjson refuses) → shape → schema → semantic rules
// → facts.
#include "eval/episode_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>


#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "eval/episode_document.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/utf8.hpp"

namespace a3::eval {
namespace {

// Why a folder entry that is not a regular file (nor a pipe) is no episode file.
std::string not_a_file_reason(mode_t mode) {
  if (S_ISDIR(mode)) return "is a folder, not an episode file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, not a regular file: not read";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file: not read";
  return "cannot stat: " + std::string(std::strerror(errno));
}

EpisodeCheck invalid(std::string rule, std::string message) {
  EpisodeCheck check;
  check.status = EpisodeStatus::kInvalid;
  check.violations.push_back({"", std::move(rule), std::move(message)});
  return check;
}

std::string syntax_message(std::string_view text, std::size_t offset,
                           rapidjson::ParseErrorCode code) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  std::string message = "not valid JSON at line " + std::to_string(line) + ", column " +
                        std::to_string(column) + " (byte " + std::to_string(offset) + "): " +
                        rapidjson::GetParseError_En(code);
  if (offset >= text.size() && code != rapidjson::kParseErrorDocumentEmpty) {
    message += " (the file ends early: truncated?)";
  }
  return message;
}

}  // namespace

const char* to_string(EpisodeStatus status) {
  switch (status) {
    case EpisodeStatus::kValid: return "valid";
    case EpisodeStatus::kFailureStub: return "failure_stub";
    case EpisodeStatus::kInvalid: return "invalid";
  }
  return "invalid";
}

EpisodeReader::EpisodeReader(const JsonSchemaValidator& validator, const ScoringProfile& profile,
                             std::uintmax_t max_file_bytes)
    : validator_(validator),
      profile_(profile),
      max_file_bytes_(max_file_bytes),
      pool_chunk_(kPoolChunkBytes),
      pool_(pool_chunk_.data(), pool_chunk_.size()) {}

EpisodeCheck EpisodeReader::check_file(const std::filesystem::path& path) {
  // O_NONBLOCK: opening a FIFO nobody writes to must not wait for a writer; then blocking reads.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return invalid("file-read", std::string("cannot open: ") + std::strerror(errno));
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !(S_ISREG(info.st_mode) || S_ISFIFO(info.st_mode))) {
    ::close(fd);
    return invalid("file-read", not_a_file_reason(info.st_mode));
  }
  // Regular files are read in one go; pipes (/dev/stdin, a FIFO) until their end (at once when
  // no one writes), within the limit.
  const bool regular = S_ISREG(info.st_mode);
  // Only a pipe needs blocking reads back (regular files ignore O_NONBLOCK): two syscalls saved
  // per episode file.
  if (!regular) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (regular && size > max_file_bytes_) {
    ::close(fd);
    return too_big(size);
  }
  // One byte more than the text: the parser works in place and needs a terminating NUL.
  std::size_t capacity = regular ? static_cast<std::size_t>(size) : std::size_t{64} << 10;
  resize_buffer(capacity);
  std::size_t got = 0;
  while (true) {
    if (got == capacity) {
      if (regular) break;
      if (got > max_file_bytes_) {
        ::close(fd);
        return too_big(got);
      }
      capacity *= 2;
      resize_buffer(capacity);
    }
    const ssize_t n = ::read(fd, buffer_.data() + got, capacity - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      return invalid("file-read", "cannot read: " + why);
    }
    if (n == 0) {
      if (regular && got < size) {
        ::close(fd);
        return invalid("file-read", "cannot read: the file shrank while reading");
      }
      break;
    }
    got += static_cast<std::size_t>(n);
  }
  if (got > max_file_bytes_) {
    ::close(fd);
    return too_big(got);
  }
  ::close(fd);
  if (!regular && got == 0) return invalid("file-read", "a FIFO or pipe with nothing written to it (no writer)");
  // A pipe cannot be read twice: keep its text for the error message of a syntax error.
  const std::string piped = regular ? std::string() : std::string(buffer_.data(), got);
  return check_buffer(got, [&path, &piped, regular] {
    if (!regular) return piped;
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  });
}

void EpisodeReader::resize_buffer(std::size_t text_bytes) {
  buffer_.resize(text_bytes + 1 + std::max(kRapidJsonPaddingBytes, kSimdjsonPaddingBytes));
}

EpisodeCheck EpisodeReader::too_big(std::uintmax_t size) const {
  return invalid("file-size", "the file is " + std::to_string(size) +
                                  " bytes, more than the limit of " +
                                  std::to_string(max_file_bytes_) + " bytes (--max-file-mb)");
}

EpisodeCheck EpisodeReader::check_text(std::string_view text) {
  if (text.size() > max_file_bytes_) return too_big(text.size());
  resize_buffer(text.size());
  std::memcpy(buffer_.data(), text.data(), text.size());
  return check_buffer(text.size(), [text] { return std::string(text); });
}

EpisodeCheck EpisodeReader::check_buffer(std::size_t size,
                                         const std::function<std::string()>& original_text) {
  // The pool keeps its first chunk between files, so a typical episode parses without malloc.
  pool_.Clear();
  rapidjson::Document document(&pool_);
  const std::string_view text(buffer_.data(), size);
  // simdjson's acceptance implies UTF-8, no NUL byte, nesting within the limit; only duplicate
  // keys remain for the shape check, and the simdjson pass says whether there are any.
  bool shape_may_fail = false;
  if (size > kMaxSimdjsonTextBytes || !fast_parser_.parse(document, text)) {
    pool_.Clear();
    document.SetNull();
    if (auto invalid_text = parse_reference(size, original_text, document)) return *invalid_text;
    shape_may_fail = true;
  } else {
    shape_may_fail = fast_parser_.has_duplicate_key();
  }
  EpisodeCheck check;
  check.attempts_used = attempts_used_or_one(document);
  // Before anything that walks the document (valijson, the rules): bounds its depth for them.
  if (shape_may_fail && shape_.check(document, check.violations)) {
    check.status = EpisodeStatus::kInvalid;
    return check;
  }
  if (!validator_.is_valid(document)) {
    check.status = EpisodeStatus::kInvalid;
    check.violations = validator_.violations(document);
    if (check.violations.empty()) {
      check.violations.push_back({"", "schema", "does not match the episode schema"});
    }
    return check;
  }
  if (is_failure_stub(document)) {
    check.status = EpisodeStatus::kFailureStub;
    return check;
  }
  check.violations = check_semantics(document, profile_);
  if (!check.violations.empty()) {
    check.status = EpisodeStatus::kInvalid;
    return check;
  }
  check.status = EpisodeStatus::kValid;
  check.facts = extract_facts(document);
  return check;
}

std::optional<EpisodeCheck> EpisodeReader::parse_reference(
    std::size_t size, const std::function<std::string()>& original_text,
    rapidjson::Document& document) {
  const std::string_view text(buffer_.data(), size);
  if (const auto bad = find_invalid_utf8(text)) {
    return invalid("json-syntax", "not UTF-8: invalid byte sequence at byte " + std::to_string(*bad));
  }
  if (std::memchr(text.data(), '\0', text.size()) != nullptr) {
    return invalid("json-syntax", "a NUL byte outside a string: not JSON text");
  }
  buffer_[size] = '\0';
  // Parsing in place saves copying every string.
  if (parser_.parse_insitu_shallow(document, buffer_.data())) return std::nullopt;
  // An error, or nesting too deep to parse recursively: again from the original text (in-place
  // parsing rewrote the buffer), iteratively, so that a file of 100k '[' cannot overflow the
  // stack (depth is checked after parsing) and errors are located as they always were.
  const std::string original = original_text();
  if (original.size() != size) return invalid("file-read", "cannot read: the file changed while reading");
  std::memcpy(buffer_.data(), original.data(), size);
  buffer_[size] = '\0';
  pool_.Clear();
  document.SetNull();
  if (const auto parsed = parser_.parse_insitu(document, buffer_.data()); parsed.IsError()) {
    return invalid("json-syntax", syntax_message(original, parsed.Offset(), parsed.Code()));
  }
  return std::nullopt;
}

}  // namespace a3::eval
