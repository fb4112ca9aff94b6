// Parameter helpers shared by the corpus-wide GoogleTest suites (3D meshing, radius-edge
// bound, dihedral window, STEP import, 2D refinement): where an input lives, the test name
// made from its path, and the inputs that are run. An input is any struct with `const char* path` (relative to
// corpus_dir(), or `data:<file>` for tests/data) and `const char* known_failure` (the
// measured reason it is not run, nullptr when it is).
#pragma once

#include <cctype>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_paths.h"

namespace delmesh::test {

/// The file of a corpus input: `data:<file>` under tests/data, anything else under the corpus.
inline std::filesystem::path corpus_input_path(const std::string& path) {
  if (path.rfind("data:", 0) == 0) return test_data_dir() / path.substr(5);
  return corpus_dir() / path;
}

/// A GoogleTest parameter name made from a file name or path: every character that is not
/// a letter or digit becomes `_`.
inline std::string parameter_name(std::string text) {
  for (char& c : text)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return text;
}

/// GoogleTest name of a parameterised corpus test: parameter_name of the input's path.
template <typename Input>
std::string corpus_test_name(const ::testing::TestParamInfo<Input>& info) {
  return parameter_name(info.param.path);
}

/// The inputs of a table that have no known failure, in table order.
template <typename Input, std::size_t N>
std::vector<Input> inputs_without_known_failure(const Input (&inputs)[N]) {
  std::vector<Input> run;
  for (const Input& input : inputs)
    if (!input.known_failure) run.push_back(input);
  return run;
}

}  // namespace delmesh::test
