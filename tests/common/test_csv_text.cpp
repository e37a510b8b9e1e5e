// CSV cells from outside text: formula leads kept as text, quoting, and an exact read back.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/csv_text.hpp"

namespace a3::common {
namespace {

TEST(CsvCell, TextThatASpreadsheetWouldRunComesOutQuotedWithAnApostrophe) {
  EXPECT_EQ(csv_cell("=HYPERLINK(\"http://x\",\"y\")"), "\"'=HYPERLINK(\"\"http://x\"\",\"\"y\"\")\"");
  EXPECT_EQ(csv_cell("+cmd|' /C calc'!A0"), "\"'+cmd|' /C calc'!A0\"");
  EXPECT_EQ(csv_cell("-2+3"), "\"'-2+3\"");
  EXPECT_EQ(csv_cell("@SUM(A1:A2)"), "\"'@SUM(A1:A2)\"");
  EXPECT_EQ(csv_cell("\t=1"), "\"'\t=1\"");
  EXPECT_EQ(csv_cell("\r=1"), "\"'\r=1\"");
}

TEST(CsvCell, NumbersAndPlainTextStayAsTheyAre) {
  for (const std::string number : {"-0.5", "+3", "-1e-05", "12", "0.25", "-.5"}) EXPECT_EQ(csv_cell(number), number);
  EXPECT_EQ(csv_cell("traffic-conflict"), "traffic-conflict");
  EXPECT_EQ(csv_cell("lognormal:30,0.5"), "\"lognormal:30,0.5\"");
  EXPECT_EQ(csv_cell("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_cell(""), "");
}

TEST(CsvFields, ReadBackEveryCellExactly) {
  const std::vector<std::string> texts = {"=1+1", "'quoted", "''", "-x", "-1", "a,b", "say \"hi\"", "", "@", "plain",
                                          "'=1"};
  std::string line;
  for (std::size_t i = 0; i < texts.size(); ++i) line += (i ? "," : "") + csv_cell(texts[i]);
  EXPECT_EQ(csv_fields(line), texts) << line;
}

TEST(CsvFields, AnUnquotedApostropheIsText) {
  EXPECT_EQ(csv_fields("'a,b'"), (std::vector<std::string>{"'a", "b'"}));
}

TEST(CsvFields, AnUnterminatedQuoteIsAnError) { EXPECT_THROW(csv_fields("a,\"b"), std::invalid_argument); }

}  // namespace
}  // namespace a3::common
