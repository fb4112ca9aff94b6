// Where tests find their inputs: small files kept in the repository (tests/data) and the
// public corpus, whose location the environment variable DELMESH_CORPUS_DIR overrides
// (.ci/run sets it).
#pragma once

#include <filesystem>

namespace delmesh::test {

/// tests/data in the source tree.
std::filesystem::path test_data_dir();
/// The corpus root (with poly2d/, poly3d/, step/, surface/).
std::filesystem::path corpus_dir();
/// The built delmesh executable, for end-to-end CLI tests.
std::filesystem::path cli_path();

}  // namespace delmesh::test
