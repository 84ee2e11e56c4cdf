// What the suite tests share: a fresh folder per test and a short copy of a published scenario.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ib::test {

// A fresh folder in the temporary directory, named after the test that asks for it.
inline std::filesystem::path fresh_test_folder(const std::string& prefix) {
  const std::filesystem::path root =
      std::filesystem::temp_directory_path() /
      (prefix + std::to_string(::getpid()) + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  return root;
}

// folder/short_free.toml: the published free vibration cut to 0.4 s, all of it scored (two impacts).
inline void write_short_free_vibration(const std::filesystem::path& folder) {
  std::ifstream in(std::string(IMPACTBENCH_SOURCE_DIR) + "/scenarios/paper/free_vibration.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"duration_s = 14.0", "duration_s = 0.4"},
                                 {"scoring_window_s = 14.0", "scoring_window_s = 0.4"},
                                 {"name = \"free_vibration\"", "name = \"short_free\""}}) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "short_free.toml") << text;
}

// How many lines a file has (a suite's runs.jsonl, runs.csv); 0 when it is absent.
inline std::size_t line_count(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// Each line of a JSON-lines file (runs.jsonl, steps.jsonl), parsed.
inline std::vector<nlohmann::json> json_lines(const std::filesystem::path& path) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

}  // namespace ib::test
