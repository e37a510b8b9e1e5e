// Outside text in a gnuplot script is read as text: gnuplot runs, prints the text, and no
// command hidden in it (system(), backquotes, macros, a line break) runs.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "common/gnuplot.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::common {
namespace {

TEST(GnuplotString, QuotesAreJoinedInAndLineBreaksBecomeSpaces) {
  EXPECT_EQ(gnuplot_string("it's"), R"('it'."'".'s')");
  EXPECT_EQ(gnuplot_string("''x"), R"(''."'".''."'".'x')");
  EXPECT_EQ(gnuplot_string("a\nb\rc"), "'a b c'");
  EXPECT_EQ(gnuplot_data_label("x\"y\tz\n"), "\"x y z \"");
}

TEST(GnuplotString, GnuplotPrintsHostileTextAndRunsNothingInIt) {
  if (!gnuplot_found()) GTEST_SKIP() << "gnuplot not on PATH (Debian: apt-get install gnuplot-nox)";
  a3::test::TempDir dir;
  const std::string marker = (dir.path() / "PWNED").string();
  const std::string texts[] = {"x'; system('touch " + marker + "-sq'); print '",
                               "x\"; system(\"touch " + marker + "-dq\"); print \"",
                               "`touch " + marker + "-bq`",
                               "@x",
                               "x\nsystem('touch " + marker + "-nl')",
                               "x\\'; system('touch " + marker + "-bs'); print '",
                               R"('''x')",
                               "it's",
                               "'"};
  std::string script = "x = 'system(\"touch " + marker + "-macro\")'\n";
  for (const std::string& text : texts) script += "print " + gnuplot_string(text) + "\n";
  const auto script_path = dir.path() / "hostile.gp";
  std::ofstream(script_path) << script;
  run_gnuplot(script_path, dir.path() / "gnuplot.log", {"y=" + gnuplot_string("'; system('touch " + marker + "-e')")});
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename().string().rfind("PWNED", 0), std::string::npos) << "ran: " << entry.path();
  }
  std::ifstream log(dir.path() / "gnuplot.log");
  std::stringstream printed;
  printed << log.rdbuf();
  EXPECT_NE(printed.str().find("x'; system('touch " + marker + "-sq'); print '\n"), std::string::npos) << printed.str();
  EXPECT_NE(printed.str().find("`touch " + marker + "-bq`"), std::string::npos) << printed.str();
  EXPECT_NE(printed.str().find("\n'''x'\nit's\n'\n"), std::string::npos) << "quotes print as they are: " << printed.str();
}

TEST(RunGnuplot, AFailingScriptThrowsWithItsLog) {
  if (!gnuplot_found()) GTEST_SKIP() << "gnuplot not on PATH (Debian: apt-get install gnuplot-nox)";
  a3::test::TempDir dir;
  const auto script_path = dir.path() / "bad.gp";
  std::ofstream(script_path) << "this is not gnuplot\n";
  try {
    run_gnuplot(script_path, dir.path() / "gnuplot.log", {});
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.gp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace a3::common
