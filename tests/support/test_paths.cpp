// Test input locations (see test_paths.h).
#include "tests/support/test_paths.h"

#include <cstdlib>

namespace delmesh::test {

std::filesystem::path test_data_dir() { return DELMESH_TEST_DATA_DIR; }

std::filesystem::path corpus_dir() {
  if (const char* env = std::getenv("DELMESH_CORPUS_DIR"); env && *env) return env;
  return DELMESH_DEFAULT_CORPUS_DIR;
}

std::filesystem::path cli_path() { return DELMESH_CLI_PATH; }

}  // namespace delmesh::test
