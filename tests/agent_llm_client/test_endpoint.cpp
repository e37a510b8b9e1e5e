// endpoint_from_environment: flags over environment, the key's sources and their order, the
// provider from the base URL, and errors that say what to set (and never show a key).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "agent/llm/llm_client.hpp"

namespace {

using a3::agent::llm::endpoint_from_environment;
using a3::agent::llm::LlmEndpoint;
using a3::agent::llm::provider_from_base_url;

const char* const kVariables[] = {"A3_LLM_BASE_URL", "A3_LLM_MODEL",   "A3_LLM_PROVIDER",
                                  "A3_LLM_API_KEY",  "A3_LLM_API_KEY_FILE", "OPENAI_API_KEY"};

// Clears the variables for the test and restores them after.
class EndpointEnvironment : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : kVariables) {
      const char* v = std::getenv(name);
      saved_.emplace_back(name, v == nullptr ? std::optional<std::string>() : std::string(v));
      ::unsetenv(name);
    }
  }
  void TearDown() override {
    for (const auto& [name, value] : saved_) {
      if (value) {
        ::setenv(name.c_str(), value->c_str(), 1);
      } else {
        ::unsetenv(name.c_str());
      }
    }
  }
  std::string error_of(const std::string& base_url_flag, const std::string& model_flag) {
    try {
      endpoint_from_environment(base_url_flag, model_flag);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

TEST_F(EndpointEnvironment, NoBaseUrlSaysWhatToSet) {
  const std::string error = error_of("", "gpt-4.1-mini");
  EXPECT_NE(error.find("A3_LLM_BASE_URL"), std::string::npos) << error;
  EXPECT_NE(error.find("--llm-base-url"), std::string::npos) << error;
}

TEST_F(EndpointEnvironment, NoModelSaysWhatToSet) {
  ::setenv("A3_LLM_BASE_URL", "http://localhost:8000/v1", 1);
  const std::string error = error_of("", "");
  EXPECT_NE(error.find("A3_LLM_MODEL"), std::string::npos) << error;
  EXPECT_NE(error.find("--llm-model"), std::string::npos) << error;
}

TEST_F(EndpointEnvironment, ABaseUrlThatIsNotHttpIsRejected) {
  const std::string error = error_of("localhost:8000/v1", "m");
  EXPECT_NE(error.find("http://"), std::string::npos) << error;
}

TEST_F(EndpointEnvironment, EnvironmentIsReadAndFlagsOverrideIt) {
  ::setenv("A3_LLM_BASE_URL", "https://api.openai.com/v1/", 1);
  ::setenv("A3_LLM_MODEL", "gpt-4.1-mini", 1);
  LlmEndpoint e = endpoint_from_environment("", "");
  EXPECT_EQ(e.base_url, "https://api.openai.com/v1");
  EXPECT_EQ(e.model, "gpt-4.1-mini");
  EXPECT_EQ(e.provider, "openai");
  EXPECT_EQ(e.api_key, "");
  EXPECT_EQ(e.temperature, 0.0);
  EXPECT_TRUE(e.json_output);

  e = endpoint_from_environment("https://openrouter.ai/api/v1", "anthropic/claude-haiku-4.5");
  EXPECT_EQ(e.base_url, "https://openrouter.ai/api/v1");
  EXPECT_EQ(e.model, "anthropic/claude-haiku-4.5");
  EXPECT_EQ(e.provider, "openrouter");

  ::setenv("A3_LLM_PROVIDER", "my-lab", 1);
  EXPECT_EQ(endpoint_from_environment("", "").provider, "my-lab");
}

TEST_F(EndpointEnvironment, KeyComesFromA3VariableThenKeyFileThenOpenAiVariable) {
  ::setenv("A3_LLM_BASE_URL", "https://api.openai.com/v1", 1);
  ::setenv("A3_LLM_MODEL", "m", 1);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("a3_key_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(file) << "  sk-from-file  \nsecond line ignored\n";

  ::setenv("OPENAI_API_KEY", "sk-from-openai", 1);
  EXPECT_EQ(endpoint_from_environment("", "").api_key, "sk-from-openai");
  ::setenv("A3_LLM_API_KEY_FILE", file.c_str(), 1);
  EXPECT_EQ(endpoint_from_environment("", "").api_key, "sk-from-file");
  ::setenv("A3_LLM_API_KEY", "sk-from-a3", 1);
  EXPECT_EQ(endpoint_from_environment("", "").api_key, "sk-from-a3");
  std::filesystem::remove(file);
}

TEST_F(EndpointEnvironment, AnUnreadableOrEmptyKeyFileIsAnError) {
  ::setenv("A3_LLM_BASE_URL", "https://api.openai.com/v1", 1);
  ::setenv("A3_LLM_MODEL", "m", 1);
  ::setenv("A3_LLM_API_KEY_FILE", "/nonexistent/a3/key", 1);
  std::string error = error_of("", "");
  EXPECT_NE(error.find("A3_LLM_API_KEY_FILE: cannot read /nonexistent/a3/key"), std::string::npos) << error;

  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("a3_empty_key_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(file) << "\n";
  ::setenv("A3_LLM_API_KEY_FILE", file.c_str(), 1);
  error = error_of("", "");
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
  std::filesystem::remove(file);
}

TEST_F(EndpointEnvironment, AKeyWithALineBreakIsRejectedWithoutShowingIt) {
  ::setenv("A3_LLM_BASE_URL", "https://api.openai.com/v1", 1);
  ::setenv("A3_LLM_MODEL", "m", 1);
  ::setenv("A3_LLM_API_KEY", "sk-secret-part\nInjected: yes", 1);
  const std::string error = error_of("", "");
  EXPECT_NE(error.find("A3_LLM_API_KEY"), std::string::npos) << error;
  EXPECT_EQ(error.find("sk-secret-part"), std::string::npos) << error;
}

TEST(ProviderFromBaseUrl, KnownHostsAndOthers) {
  EXPECT_EQ(provider_from_base_url("https://api.openai.com/v1"), "openai");
  EXPECT_EQ(provider_from_base_url("https://openrouter.ai/api/v1"), "openrouter");
  EXPECT_EQ(provider_from_base_url("https://api.anthropic.com/v1/"), "anthropic");
  EXPECT_EQ(provider_from_base_url("https://generativelanguage.googleapis.com/v1beta/openai"), "google");
  EXPECT_EQ(provider_from_base_url("http://localhost:8000/v1"), "local");
  EXPECT_EQ(provider_from_base_url("http://127.0.0.1:8088/v1"), "local");
  EXPECT_EQ(provider_from_base_url("http://[::1]:11434/v1"), "local");
  EXPECT_EQ(provider_from_base_url("https://GPU-Box.lab.example:8443/v1"), "gpu-box.lab.example");
  EXPECT_EQ(provider_from_base_url("https://notapi.openai.com.evil.example/v1"), "notapi.openai.com.evil.example");
}

}  // namespace
