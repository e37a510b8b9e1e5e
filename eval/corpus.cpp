// Corpus discovery.
#include "eval/corpus.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <system_error>

#include "eval/rig_episode_label.hpp"

namespace a3::eval {
namespace fs = std::filesystem;

namespace {

std::optional<int> parse_digits(const std::string& s, std::size_t begin, std::size_t end) {
  if (begin >= end || end - begin > 9) return std::nullopt;
  int value = 0;
  for (std::size_t i = begin; i < end; ++i) {
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) return std::nullopt;
    value = value * 10 + (s[i] - '0');
  }
  return value;
}

}  // namespace

std::optional<EpisodeName> parse_episode_name(const std::string& name) {
  // sc-<digits>-ep-<digits>.json
  constexpr std::string_view kSuffix = ".json";
  if (name.rfind("sc-", 0) != 0 || name.size() < 3 + 1 + 4 + 1 + kSuffix.size() ||
      name.compare(name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0) {
    return std::nullopt;
  }
  const std::size_t ep = name.find("-ep-", 3);
  if (ep == std::string::npos) return std::nullopt;
  const auto scenario = parse_digits(name, 3, ep);
  const auto episode = parse_digits(name, ep + 4, name.size() - kSuffix.size());
  if (!scenario || !episode) return std::nullopt;
  return EpisodeName{*scenario, *episode};
}

void attribute_model(EpisodeFile& file, const CorpusOptions& options) {
  if (!options.model_override.empty()) {
    file.model = options.model_override;
    file.domain = options.domain_override;
    return;
  }
  const fs::path absolute = fs::absolute(file.path).lexically_normal();
  const fs::path domain_dir = absolute.parent_path();
  const fs::path model_dir = domain_dir.parent_path();
  const fs::path provider_dir = model_dir.parent_path();
  file.domain = domain_dir.filename().string();
  const std::string provider = provider_dir.filename().string();
  file.model = provider.empty() ? model_dir.filename().string()
                                : provider + "/" + model_dir.filename().string();
}

CorpusWalker::CorpusWalker(std::vector<fs::path> roots, CorpusOptions options)
    : roots_(std::move(roots)), options_(std::move(options)) {
  for (const auto& root : roots_) {
    std::error_code ec;
    if (!fs::exists(root, ec)) {
      throw std::invalid_argument(root.string() + ": no such file or folder");
    }
  }
}

EpisodeFile CorpusWalker::rig_episode(const fs::path& path) {
  EpisodeFile file{path, {}, {}, std::nullopt};
  attribute_model(file, options_);
  const auto label = read_rig_episode_label(path);
  if (!label) return file;  // not a3rig's or unreadable: the check says what is wrong
  if (options_.model_override.empty()) {
    file.model = label->model;
    file.domain = options_.domain_override;
  }
  const auto numbered = rig_scenario_numbers_.emplace(label->scenario, static_cast<int>(rig_scenario_numbers_.size()));
  file.name = EpisodeName{numbered.first->second, static_cast<int>(label->seed & 0x7fffffff)};
  return file;
}

void CorpusWalker::push_directory(const fs::path& dir) {
  Frame frame;
  struct stat info {};
  if (::stat(dir.c_str(), &info) == 0) {
    frame.device = static_cast<uint64_t>(info.st_dev);
    frame.inode = static_cast<uint64_t>(info.st_ino);
    for (const Frame& ancestor : stack_) {
      if (ancestor.device == frame.device && ancestor.inode == frame.inode) {
        warnings_.push_back(dir.string() + ": a folder loop (a symlink back to a folder above it): "
                                           "not searched again");
        return;
      }
    }
  }
  std::error_code ec;
  // No skip_permission_denied: it would turn an unreadable folder into an empty one, unreported.
  fs::directory_iterator it(dir, ec);
  if (ec) {
    warnings_.push_back(dir.string() + ": cannot list: " + ec.message());
    return;
  }
  for (const auto end = fs::directory_iterator(); it != end; it.increment(ec)) {
    if (ec) {
      warnings_.push_back(dir.string() + ": listing stopped: " + ec.message());
      break;
    }
    frame.entries.push_back(*it);
  }
  // Entries of one folder differ only in their names (no '/'), so comparing the whole text is
  // path order, without path::compare splitting both into components each time.
  std::sort(frame.entries.begin(), frame.entries.end(),
            [](const auto& a, const auto& b) { return a.path().native() < b.path().native(); });
  EpisodeFile probe{dir / "probe", {}, {}, std::nullopt};
  attribute_model(probe, options_);
  frame.model = std::move(probe.model);
  frame.domain = std::move(probe.domain);
  stack_.push_back(std::move(frame));
}

std::optional<EpisodeFile> CorpusWalker::next() {
  while (true) {
    if (stack_.empty()) {
      if (next_root_ >= roots_.size()) return std::nullopt;
      const fs::path& root = roots_[next_root_++];
      std::error_code ec;
      if (fs::is_directory(root, ec)) {
        push_directory(root);
        continue;
      }
      if (root.filename() == kRigEpisodeFileName) return rig_episode(root);
      EpisodeFile file{root, {}, {}, parse_episode_name(root.filename().string())};
      attribute_model(file, options_);
      return file;
    }
    Frame& frame = stack_.back();
    if (frame.next >= frame.entries.size()) {
      stack_.pop_back();
      continue;
    }
    const fs::directory_entry& entry = frame.entries[frame.next++];
    const fs::path path = entry.path();
    std::error_code ec;
    // Whatever it is (a FIFO, a device, a folder, a dangling or looping link), an entry named
    // as an episode is one: EpisodeReader::check_file says why it is invalid, without blocking.
    if (auto parsed = parse_episode_name(path.filename().string())) {
      return EpisodeFile{path, frame.model, frame.domain, parsed};
    }
    if (path.filename() == kRigEpisodeFileName) return rig_episode(path);
    // The entry's type comes from the folder listing; only symlinks need a stat.
    if (entry.is_directory(ec)) {
      // Symlinked folders are followed (loops are refused in push_directory); depth is capped.
      if (stack_.size() < 64) {
        push_directory(path);
      } else {
        warnings_.push_back(path.string() + ": folder nesting deeper than 64, not searched");
      }
      continue;
    }
    // A symlink whose target cannot be read (dangling, or a loop the kernel stops with ELOOP).
    if (ec) {
      warnings_.push_back(path.string() + ": cannot read: " + ec.message());
      continue;
    }
    if (entry.is_regular_file(ec) && path.extension() == ".json") ++ignored_json_;
  }
}

}  // namespace a3::eval
