// Parsing and expanding the sweep grid, shards, and the folder of each cell.
#include "rigs/sweep/sweep_grid.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <stdexcept>

#include "agent/conversation/think_time.hpp"
#include "linkemu/network_state.hpp"

namespace a3::rigs::sweep {
namespace {

std::string trim(const std::string& s) {
  const auto begin = s.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  const auto end = s.find_last_not_of(" \t");
  return s.substr(begin, end - begin + 1);
}

std::vector<std::string> raw_items(const std::string& text, const std::string& flag) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    const std::string item = trim(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty()) {
      throw std::invalid_argument(flag + " '" + text + "': empty item at character " + std::to_string(start + 1) +
                                  " (expected a comma-separated list)");
    }
    out.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

template <typename T>
void require_distinct(const std::vector<T>& items, const std::string& flag, const std::string& text) {
  std::set<T> seen;
  for (const auto& item : items) {
    if (!seen.insert(item).second) {
      if constexpr (std::is_same_v<T, std::string>) {
        throw std::invalid_argument(flag + " '" + text + "': '" + item + "' is listed twice");
      } else {
        throw std::invalid_argument(flag + " '" + text + "': " + std::to_string(item) + " is listed twice");
      }
    }
  }
}

void require_distinct_folders(const std::vector<std::string>& items, const std::string& flag) {
  std::map<std::string, std::string> by_folder;
  for (const auto& item : items) {
    const auto [it, inserted] = by_folder.emplace(folder_name(item), item);
    if (!inserted) {
      throw std::invalid_argument(flag + ": '" + it->second + "' and '" + item + "' would share the folder '" +
                                  it->first + "'; rename one of them");
    }
  }
}

uint64_t parse_seed(const std::string& item, const std::string& flag, const std::string& text) {
  if (item.empty() || !std::all_of(item.begin(), item.end(), [](unsigned char c) { return std::isdigit(c); })) {
    throw std::invalid_argument(flag + " '" + text + "': '" + item +
                                "' is not a non-negative integer (expected e.g. 1,2,3 or 1-5)");
  }
  try {
    return std::stoull(item);
  } catch (const std::out_of_range&) {
    throw std::invalid_argument(flag + " '" + text + "': '" + item + "' is too large for a 64-bit seed");
  }
}

}  // namespace

std::vector<std::string> expand_generated_missions(const std::vector<std::string>& scenarios, const std::string& flag) {
  std::vector<std::string> out;
  for (const auto& item : scenarios) {
    if (item.rfind("gen:", 0) != 0) {
      out.push_back(item);
      continue;
    }
    const auto colon = item.find(':', 4);
    const std::string count = item.substr(4, colon == std::string::npos ? std::string::npos : colon - 4);
    const std::string knobs = colon == std::string::npos ? "" : item.substr(colon);
    const bool range = count.find('-') != std::string::npos;
    const std::vector<uint64_t> seeds = parse_seeds(range ? count : "1-" + count, flag + " " + item);
    for (const uint64_t seed : seeds) out.push_back("gen:" + std::to_string(seed) + knobs);
  }
  return out;
}

std::vector<std::string> split_list(const std::string& text, const std::string& flag) {
  std::vector<std::string> items = raw_items(text, flag);
  require_distinct(items, flag, text);
  return items;
}

std::vector<std::string> split_think_times(const std::string& text, const std::string& flag) {
  const std::vector<std::string> raw = raw_items(text, flag);
  std::vector<std::string> specs;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    std::string spec = raw[i];
    const std::string kind = spec.substr(0, spec.find(':'));
    const bool two_parameters = kind == "uniform" || kind == "normal" || kind == "lognormal";
    if (two_parameters && spec.find(',') == std::string::npos) {
      if (i + 1 == raw.size()) {
        throw std::invalid_argument(flag + " '" + text + "': '" + spec + "' needs a second parameter (" + kind +
                                    ":A,B)");
      }
      spec += "," + raw[++i];
    }
    try {
      (void)agent::ThinkTime::parse(spec);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(flag + ": " + e.what());
    }
    specs.push_back(spec);
  }
  require_distinct(specs, flag, text);
  return specs;
}

std::vector<uint64_t> parse_seeds(const std::string& text, const std::string& flag) {
  std::vector<uint64_t> seeds;
  for (const std::string& item : raw_items(text, flag)) {
    const auto dash = item.find('-');
    if (dash == std::string::npos) {
      seeds.push_back(parse_seed(item, flag, text));
      continue;
    }
    const uint64_t first = parse_seed(trim(item.substr(0, dash)), flag, text);
    const uint64_t last = parse_seed(trim(item.substr(dash + 1)), flag, text);
    if (last < first) {
      throw std::invalid_argument(flag + " '" + text + "': range '" + item + "' ends before it starts");
    }
    if (last - first >= 100000) {
      throw std::invalid_argument(flag + " '" + text + "': range '" + item + "' holds more than 100000 seeds");
    }
    for (uint64_t s = first; s <= last; ++s) seeds.push_back(s);
  }
  require_distinct(seeds, flag, text);
  return seeds;
}

SweepAxes make_axes(const std::string& scenarios, const std::string& agents, const std::string& think_times,
                    const std::string& slices, const std::string& seeds) {
  SweepAxes axes;
  axes.scenarios = expand_generated_missions(raw_items(scenarios, "--scenarios"), "--scenarios");
  require_distinct(axes.scenarios, "--scenarios", scenarios);
  axes.agents = split_list(agents, "--agents");
  axes.think_times = split_think_times(think_times, "--think-times");
  axes.slices = split_list(slices, "--slices");
  axes.seeds = parse_seeds(seeds, "--seeds");
  for (const auto& slice : axes.slices) {
    const auto names = linkemu::slice_names();
    if (std::find(names.begin(), names.end(), slice) == names.end()) {
      throw std::invalid_argument("--slices: '" + slice + "' is not a 6G slice (expected eMBB, URLLC or mMTC)");
    }
  }
  for (const auto& agent : axes.agents) {
    if (agent != "scripted" && agent != "llm" && agent.rfind("replay:", 0) != 0) {
      throw std::invalid_argument("--agents: '" + agent +
                                  "' is not an agent (expected scripted, llm or replay:<episode.json>)");
    }
  }
  require_distinct_folders(axes.scenarios, "--scenarios");
  require_distinct_folders(axes.agents, "--agents");
  require_distinct_folders(axes.think_times, "--think-times");
  return axes;
}

std::vector<SweepCell> expand_grid(const SweepAxes& axes) {
  std::vector<SweepCell> cells;
  for (const auto& scenario : axes.scenarios) {
    for (const auto& agent : axes.agents) {
      for (const auto& think : axes.think_times) {
        const double mean_s = agent::ThinkTime::parse(think).mean_s();
        for (const auto& slice : axes.slices) {
          for (const uint64_t seed : axes.seeds) {
            cells.push_back({cells.size(), scenario, agent, think, mean_s, slice, seed});
          }
        }
      }
    }
  }
  return cells;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  auto number = [&](const std::string& part) {
    if (part.empty() || part.size() > 6 ||
        !std::all_of(part.begin(), part.end(), [](unsigned char c) { return std::isdigit(c); })) {
      throw std::invalid_argument("--shard '" + text + "': expected i/N with integers 0 <= i < N (e.g. 0/4)");
    }
    return std::stoi(part);
  };
  if (slash == std::string::npos) {
    throw std::invalid_argument("--shard '" + text + "': expected i/N with integers 0 <= i < N (e.g. 0/4)");
  }
  Shard shard{number(text.substr(0, slash)), number(text.substr(slash + 1))};
  if (shard.count < 1 || shard.index >= shard.count) {
    throw std::invalid_argument("--shard '" + text + "': the shard index must be in 0.." +
                                std::to_string(std::max(shard.count - 1, 0)) + " and N at least 1");
  }
  return shard;
}

bool in_shard(const SweepCell& cell, const Shard& shard) {
  return cell.index % static_cast<std::size_t>(shard.count) == static_cast<std::size_t>(shard.index);
}

std::vector<SweepCell> cells_of_shard(const std::vector<SweepCell>& grid, const Shard& shard) {
  std::vector<SweepCell> out;
  for (const auto& cell : grid) {
    if (in_shard(cell, shard)) out.push_back(cell);
  }
  return out;
}

std::string folder_name(const std::string& item) {
  std::string out;
  for (const unsigned char c : item) {
    const bool keep = std::isalnum(c) || c == '.' || c == ',' || c == '+' || c == '-' || c == '=';
    out += keep ? static_cast<char>(c) : '_';
  }
  if (out.find_first_not_of('.') == std::string::npos) out = std::string(out.size() + 1, '_');
  return out;
}

std::filesystem::path cell_dir(const std::filesystem::path& out_dir, const SweepCell& cell) {
  return out_dir / "cells" / folder_name(cell.scenario) / folder_name(cell.agent) /
         ("think-" + folder_name(cell.think_time)) / folder_name(cell.slice) / ("seed-" + std::to_string(cell.seed));
}

}  // namespace a3::rigs::sweep
