// The label a3rig's own episodes carry (`_meta.model`, `_rig.*`): read from a whole file, and
// refused, never crashed on, when the text is cut short or damaged anywhere.
#include <gtest/gtest.h>

#include <string>

#include "eval/rig_episode_label.hpp"

namespace a3::eval {
namespace {

const std::string kLabelled =
    R"({"_meta":{"model":"reference"},"dialogue":[{"role":"user","content":"fly"}],)"
    R"("_rig":{"scenario":"parcel-delivery","seed":3,"think_time":"10","slice":"URLLC"}})";

TEST(RigEpisodeLabel, ReadsModelThinkTimeSliceScenarioAndSeed) {
  const auto label = rig_episode_label_from_text(kLabelled);
  ASSERT_TRUE(label.has_value());
  EXPECT_EQ(label->model, "reference, think 10, URLLC");
  EXPECT_EQ(label->scenario, "parcel-delivery");
  EXPECT_EQ(label->seed, 3);
}

TEST(RigEpisodeLabel, AnEpisodeWithoutTheRigsFieldsHasNoLabel) {
  EXPECT_FALSE(rig_episode_label_from_text(R"({"_meta":{"model":"m"}})").has_value());
  EXPECT_FALSE(rig_episode_label_from_text(R"({"_rig":{"scenario":"s"}})").has_value());
  EXPECT_FALSE(rig_episode_label_from_text(R"({"_meta":{"model":""},"_rig":{"scenario":"s"}})").has_value());
}

// Every prefix and every single-byte damage: a label only from the whole, valid text. (The
// episode fuzz target found the on-demand reader touching a dead parser after such damage.)
TEST(RigEpisodeLabel, CutOrDamagedTextIsRefusedAtEveryByte) {
  for (std::size_t length = 0; length < kLabelled.size(); ++length)
    EXPECT_FALSE(rig_episode_label_from_text(kLabelled.substr(0, length)).has_value()) << length;
  for (std::size_t at = 0; at < kLabelled.size(); ++at) {
    for (const char damage : {'"', '{', '}', ',', '\\', '\0'}) {
      std::string text = kLabelled;
      text[at] = damage;
      const auto label = rig_episode_label_from_text(text);
      if (label) {
        EXPECT_FALSE(label->model.empty()) << at;
      }
    }
  }
}

}  // namespace
}  // namespace a3::eval
