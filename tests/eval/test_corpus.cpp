// Corpus discovery (eval/corpus.hpp): episode file names, model attribution from the
// provider/model/domain folders, and CorpusWalker's order, counting and errors on a temp tree.
#include <gtest/gtest.h>

#include "eval/corpus.hpp"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using a3::eval::attribute_model;
using a3::eval::CorpusOptions;
using a3::eval::CorpusWalker;
using a3::eval::EpisodeFile;
using a3::eval::parse_episode_name;

// ---- parse_episode_name -----------------------------------------------------------------------

TEST(ParseEpisodeName, ReadsScenarioAndEpisodeNumbers) {
  struct Case {
    const char* name;
    int scenario, episode;
  };
  for (const Case& c : {Case{"sc-0001-ep-01.json", 1, 1}, Case{"sc-0042-ep-07.json", 42, 7},
                        Case{"sc-0000-ep-00.json", 0, 0}, Case{"sc-1-ep-2.json", 1, 2},
                        Case{"sc-0050-ep-123.json", 50, 123},
                        Case{"sc-123456789-ep-987654321.json", 123456789, 987654321}}) {
    const auto parsed = parse_episode_name(c.name);
    ASSERT_TRUE(parsed.has_value()) << c.name;
    EXPECT_EQ(parsed->scenario, c.scenario) << c.name;
    EXPECT_EQ(parsed->episode, c.episode) << c.name;
  }
}

TEST(ParseEpisodeName, RejectsOtherNames) {
  for (const char* name : {
           "",
           ".json",
           "sc-0001-ep-01",             // no extension
           "sc-0001-ep-01.JSON",        // the extension is case sensitive
           "sc-0001-ep-01.json.bak",
           "sc-0001-ep-01.jsonl",
           "sc-0001-ep-01.json ",
           "SC-0001-ep-01.json",
           "xsc-0001-ep-01.json",
           " sc-0001-ep-01.json",
           "sc-0001_ep-01.json",
           "sc-0001-EP-01.json",
           "sc--ep-01.json",            // no scenario digits
           "sc-0001-ep-.json",          // no episode digits
           "sc-00a1-ep-01.json",
           "sc-0001-ep-0x1.json",
           "sc-+001-ep-01.json",
           "sc--001-ep-01.json",
           "sc- 001-ep-01.json",
           "sc-0001-ep-01-ep-02.json",
           "sc-0001-ep-01.json.json",
           "sc-1234567890-ep-01.json",  // ten digits would overflow int
           "sc-0001-ep-1234567890.json",
           "notes.json",
       }) {
    EXPECT_FALSE(parse_episode_name(name).has_value()) << '"' << name << '"';
  }
}

// ---- attribute_model --------------------------------------------------------------------------

EpisodeFile attributed(const fs::path& path, const CorpusOptions& options = {}) {
  EpisodeFile file{path, "stale", "stale", std::nullopt};
  attribute_model(file, options);
  return file;
}

TEST(AttributeModel, TakesProviderModelAndDomainFromTheLastThreeFolders) {
  auto file = attributed("/data/eval_runs/openai/gpt-5.1-chat/uav/sc-0001-ep-01.json");
  EXPECT_EQ(file.model, "openai/gpt-5.1-chat");
  EXPECT_EQ(file.domain, "uav");

  file = attributed("/x/google/gemini-3-pro-preview/maritime/anything.json");
  EXPECT_EQ(file.model, "google/gemini-3-pro-preview");
  EXPECT_EQ(file.domain, "maritime");

  // ".." and "." are resolved before the folders are read.
  file = attributed("/runs/anthropic/claude-haiku-4.5/other/../uav/./sc-0002-ep-01.json");
  EXPECT_EQ(file.model, "anthropic/claude-haiku-4.5");
  EXPECT_EQ(file.domain, "uav");

  // Right under the root there is no provider folder: the model is the one folder name.
  file = attributed("/llama/uav/sc-0001-ep-01.json");
  EXPECT_EQ(file.model, "llama");
  EXPECT_EQ(file.domain, "uav");
}

TEST(AttributeModel, ResolvesRelativePathsAgainstTheWorkingFolder) {
  const auto file = attributed("openai/chatgpt-4o-latest/uav/sc-0003-ep-01.json");
  EXPECT_EQ(file.model, "openai/chatgpt-4o-latest");
  EXPECT_EQ(file.domain, "uav");
  // A file directly in the working folder takes its names from the working folder's parents.
  const fs::path cwd = fs::current_path();
  const auto here = attributed("sc-0001-ep-01.json");
  EXPECT_EQ(here.domain, cwd.filename().string());
}

TEST(AttributeModel, ModelOverrideReplacesTheFolders) {
  CorpusOptions options;
  options.model_override = "local/llama-3-8b";
  auto file = attributed("/data/openai/gpt-5.1-chat/uav/sc-0001-ep-01.json", options);
  EXPECT_EQ(file.model, "local/llama-3-8b");
  EXPECT_EQ(file.domain, "uav");  // the default domain

  options.domain_override = "maritime";
  file = attributed("flat/sc-0001-ep-01.json", options);
  EXPECT_EQ(file.model, "local/llama-3-8b");
  EXPECT_EQ(file.domain, "maritime");

  // A domain override alone (no model) does not apply: the folders decide.
  CorpusOptions domain_only;
  domain_only.domain_override = "maritime";
  file = attributed("/data/openai/gpt-5.1-chat/uav/sc-0001-ep-01.json", domain_only);
  EXPECT_EQ(file.model, "openai/gpt-5.1-chat");
  EXPECT_EQ(file.domain, "uav");
}

// ---- CorpusWalker -----------------------------------------------------------------------------

class TempTree {
 public:
  TempTree() {
    std::string pattern = (fs::temp_directory_path() / "a3-corpus-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    root_ = pattern;
  }
  ~TempTree() {
    // Give back the permissions a test took away (each folder before it is entered), then remove.
    std::error_code ec;
    for (fs::recursive_directory_iterator it(root_, ec), end; !ec && it != end; it.increment(ec)) {
      fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
    }
    fs::remove_all(root_, ec);
  }
  TempTree(const TempTree&) = delete;
  TempTree& operator=(const TempTree&) = delete;

  const fs::path& root() const { return root_; }
  fs::path file(const std::string& relative) const {
    const fs::path path = root_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "{}";
    return path;
  }
  fs::path folder(const std::string& relative) const {
    fs::create_directories(root_ / relative);
    return root_ / relative;
  }

 private:
  fs::path root_;
};

std::vector<EpisodeFile> walk_all(CorpusWalker& walker) {
  std::vector<EpisodeFile> files;
  while (auto file = walker.next()) files.push_back(std::move(*file));
  EXPECT_FALSE(walker.next().has_value()) << "next() after the end";
  return files;
}

std::vector<std::string> relative_paths(const std::vector<EpisodeFile>& files, const fs::path& root) {
  std::vector<std::string> out;
  for (const EpisodeFile& f : files) out.push_back(f.path.lexically_relative(root).string());
  return out;
}

// A small α³-Bench-like tree, its files created in the listed order or the reverse.
void build_corpus(const TempTree& tree, bool reverse = true) {
  std::vector<std::string> files = {
      "runs/openai/gpt-5.1-chat/uav/sc-0010-ep-01.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0002-ep-01.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0001-ep-02.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0001-ep-01.json",
      "runs/openai/gpt-5.1-chat/uav/notes.json",               // ignored .json
      "runs/openai/gpt-5.1-chat/uav/README.md",                // other file
      "runs/openai/gpt-5.1-chat/uav/sc-0003-ep-01.json.bak",   // other file
      "runs/openai/gpt-5.1-chat/summary.json",                 // ignored .json
      "runs/anthropic/claude-haiku-4.5/uav/sc-0001-ep-01.json",
      "runs/anthropic/claude-haiku-4.5/maritime/sc-0005-ep-01.json",
      "runs/anthropic/claude-haiku-4.5/maritime/sc-0005-ep-01.json.json",  // ignored .json
      // A folder that looks like an episode file is returned (an invalid entry), not searched.
      "runs/google/gemini-3-pro-preview/uav/sc-0007-ep-01.json/sc-0008-ep-01.json",
  };
  if (reverse) std::reverse(files.begin(), files.end());
  for (const std::string& relative : files) tree.file(relative);
  tree.folder("runs/google/empty/uav");
}

TEST(CorpusWalker, WalksNestedFoldersInSortedOrderWithAttribution) {
  TempTree tree;
  build_corpus(tree);
  CorpusWalker walker({tree.root() / "runs"}, {});
  const auto files = walk_all(walker);

  const std::vector<std::string> expected = {
      "runs/anthropic/claude-haiku-4.5/maritime/sc-0005-ep-01.json",
      "runs/anthropic/claude-haiku-4.5/uav/sc-0001-ep-01.json",
      "runs/google/gemini-3-pro-preview/uav/sc-0007-ep-01.json",  // a folder: an (invalid) entry, not searched
      "runs/openai/gpt-5.1-chat/uav/sc-0001-ep-01.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0001-ep-02.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0002-ep-01.json",
      "runs/openai/gpt-5.1-chat/uav/sc-0010-ep-01.json",
  };
  EXPECT_EQ(relative_paths(files, tree.root()), expected);
  ASSERT_EQ(files.size(), expected.size());

  EXPECT_EQ(files[0].model, "anthropic/claude-haiku-4.5");
  EXPECT_EQ(files[0].domain, "maritime");
  EXPECT_EQ(files[1].domain, "uav");
  EXPECT_EQ(files[2].model, "google/gemini-3-pro-preview");
  EXPECT_EQ(files[2].domain, "uav");
  for (std::size_t i = 3; i < files.size(); ++i) {
    EXPECT_EQ(files[i].model, "openai/gpt-5.1-chat") << files[i].path;
    EXPECT_EQ(files[i].domain, "uav") << files[i].path;
  }
  ASSERT_TRUE(files[4].name.has_value());
  EXPECT_EQ(files[4].name->scenario, 1);
  EXPECT_EQ(files[4].name->episode, 2);
  ASSERT_TRUE(files[6].name.has_value());
  EXPECT_EQ(files[6].name->scenario, 10);

  EXPECT_EQ(walker.ignored_json_files(), 3u);  // notes.json, summary.json, *.json.json
  EXPECT_TRUE(walker.warnings().empty());
}

TEST(CorpusWalker, OrderDoesNotDependOnTheOrderFilesWereCreated) {
  TempTree forward, backward;
  build_corpus(forward, false);
  build_corpus(backward, true);
  CorpusWalker first({forward.root()}, {});
  CorpusWalker second({backward.root()}, {});
  const auto a = relative_paths(walk_all(first), forward.root());
  const auto b = relative_paths(walk_all(second), backward.root());
  EXPECT_EQ(a.size(), 7u);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
}

TEST(CorpusWalker, FlatFolderWithModelOverride) {
  TempTree tree;
  for (const char* name : {"sc-0002-ep-01.json", "sc-0001-ep-01.json", "results.json", "log.txt"}) {
    tree.file(std::string("flat/") + name);
  }
  CorpusOptions options;
  options.model_override = "local/llama-3-8b";
  CorpusWalker walker({tree.root() / "flat"}, options);
  const auto files = walk_all(walker);
  EXPECT_EQ(relative_paths(files, tree.root()),
            (std::vector<std::string>{"flat/sc-0001-ep-01.json", "flat/sc-0002-ep-01.json"}));
  for (const EpisodeFile& f : files) {
    EXPECT_EQ(f.model, "local/llama-3-8b");
    EXPECT_EQ(f.domain, "uav");
  }
  EXPECT_EQ(walker.ignored_json_files(), 1u);
}

TEST(CorpusWalker, TakesFileRootsAsTheyAreInTheGivenOrder) {
  TempTree tree;
  build_corpus(tree);
  const fs::path episode = tree.root() / "runs/openai/gpt-5.1-chat/uav/sc-0010-ep-01.json";
  const fs::path notes = tree.root() / "runs/openai/gpt-5.1-chat/uav/notes.json";
  const fs::path folder = tree.root() / "runs/anthropic/claude-haiku-4.5/uav";
  CorpusWalker walker({episode, notes, folder}, {});
  const auto files = walk_all(walker);
  ASSERT_EQ(files.size(), 3u);

  EXPECT_EQ(files[0].path, episode);
  EXPECT_EQ(files[0].model, "openai/gpt-5.1-chat");
  EXPECT_EQ(files[0].domain, "uav");
  ASSERT_TRUE(files[0].name.has_value());
  EXPECT_EQ(files[0].name->scenario, 10);
  EXPECT_EQ(files[0].name->episode, 1);

  // Named explicitly, a file is scored whatever its name.
  EXPECT_EQ(files[1].path, notes);
  EXPECT_FALSE(files[1].name.has_value());
  EXPECT_EQ(files[1].model, "openai/gpt-5.1-chat");

  EXPECT_EQ(files[2].path, folder / "sc-0001-ep-01.json");
  EXPECT_EQ(files[2].model, "anthropic/claude-haiku-4.5");
  EXPECT_EQ(walker.ignored_json_files(), 0u);
}

TEST(CorpusWalker, MissingRootThrowsBeforeWalking) {
  TempTree tree;
  build_corpus(tree);
  const fs::path missing = tree.root() / "no-such-folder";
  EXPECT_THROW(CorpusWalker({missing}, {}), std::invalid_argument);
  // One missing root among good ones is enough.
  try {
    CorpusWalker walker({tree.root() / "runs", missing}, {});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
}

TEST(CorpusWalker, EmptyRootListAndEmptyFolderGiveNothing) {
  TempTree tree;
  CorpusWalker none({}, {});
  EXPECT_FALSE(none.next().has_value());
  CorpusWalker empty({tree.folder("empty")}, {});
  EXPECT_FALSE(empty.next().has_value());
  EXPECT_EQ(empty.ignored_json_files(), 0u);
}

// Symlinked folders are followed, but a link back to a folder above is not entered again:
// each file is found once, and the loop is reported.
TEST(CorpusWalker, FolderSymlinkLoopsEndWithAWarning) {
  TempTree tree;
  const fs::path self = tree.folder("self");
  tree.file("self/sc-0001-ep-01.json");
  fs::create_directory_symlink(self, self / "again");  // self/again is self
  const fs::path up = tree.folder("up/loop");
  tree.file("up/loop/sc-0001-ep-01.json");
  fs::create_directory_symlink("..", up / "back");  // up/loop/back is up

  for (const fs::path& root : {self, up}) {
    CorpusWalker walker({root}, {});
    const auto files = walk_all(walker);
    EXPECT_EQ(files.size(), 1u) << root;
    ASSERT_EQ(walker.warnings().size(), 1u) << root;
    EXPECT_EQ(walker.warnings()[0].rfind(root.string(), 0), 0u) << walker.warnings()[0];
    EXPECT_NE(walker.warnings()[0].find("folder loop"), std::string::npos) << walker.warnings()[0];
  }
}

// A dangling link named like an episode is an episode entry (the reader finds it invalid,
// tests/eval/test_corpus_faults.cpp); any other dangling link is reported.
TEST(CorpusWalker, ReportsADanglingSymlink) {
  TempTree tree;
  tree.file("p/m/uav/sc-0001-ep-01.json");
  fs::create_symlink(tree.root() / "gone.json", tree.root() / "p/m/uav/sc-0002-ep-01.json");
  fs::create_symlink(tree.root() / "gone", tree.root() / "p/m/uav/notes");
  CorpusWalker walker({tree.root()}, {});
  const auto files = walk_all(walker);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].path.filename(), "sc-0001-ep-01.json");
  EXPECT_EQ(files[1].path.filename(), "sc-0002-ep-01.json");
  ASSERT_EQ(walker.warnings().size(), 1u);
  EXPECT_NE(walker.warnings()[0].find("notes: cannot read"), std::string::npos) << walker.warnings()[0];
}

// An unreadable folder is reported, not silently taken for an empty one. Root reads every
// folder, so as root the walk runs in a child process that has become `nobody`.
TEST(CorpusWalker, ReportsAFolderItCannotList) {
  TempTree tree;
  tree.file("p/m/uav/sc-0001-ep-01.json");
  tree.file("p/m/locked/sc-0002-ep-01.json");
  for (const auto& entry : fs::recursive_directory_iterator(tree.root())) {
    fs::permissions(entry.path(), fs::perms::all, fs::perm_options::add);
  }
  fs::permissions(tree.root(), fs::perms::all, fs::perm_options::add);
  fs::permissions(tree.root() / "p/m/locked", fs::perms::none);

  enum Outcome { kOk = 0, kWrongFiles = 1, kNoWarning = 2, kCannotDropPrivileges = 3 };
  auto walk = [&]() -> Outcome {
    CorpusWalker walker({tree.root()}, {});
    std::vector<EpisodeFile> files;
    while (auto file = walker.next()) files.push_back(std::move(*file));
    if (files.size() != 1 || files[0].path.filename() != "sc-0001-ep-01.json") return kWrongFiles;
    const auto& warnings = walker.warnings();
    if (warnings.size() != 1 || warnings[0].find("locked") == std::string::npos ||
        warnings[0].find("cannot list") == std::string::npos) {
      return kNoWarning;
    }
    return kOk;
  };

  Outcome outcome;
  if (geteuid() != 0) {
    outcome = walk();
  } else {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      constexpr uid_t kNobody = 65534;
      if (setgid(kNobody) != 0 || setuid(kNobody) != 0) _exit(kCannotDropPrivileges);
      _exit(walk());
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    outcome = static_cast<Outcome>(WEXITSTATUS(status));
    if (outcome == kCannotDropPrivileges) GTEST_SKIP() << "running as root and cannot become nobody";
  }
  EXPECT_NE(outcome, kWrongFiles) << "expected only the readable folder's episode";
  EXPECT_NE(outcome, kNoWarning) << "the unreadable folder p/m/locked was not reported in warnings()";
  EXPECT_EQ(outcome, kOk);
}

}  // namespace
