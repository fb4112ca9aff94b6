// A fresh, empty directory per test for files the test writes, removed afterwards.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace delmesh::test {

class ScratchDir {
 public:
  /// Creates <temp>/delmesh-<tag>-<pid>-<counter>, empty.
  explicit ScratchDir(std::string_view tag);
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir();

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }
  /// Writes `content` to the file `name` in the directory and returns its path.
  std::filesystem::path write(std::string_view name, std::string_view content) const;

 private:
  std::filesystem::path path_;
};

/// The whole content of a file ("" if it cannot be read).
std::string read_file(const std::filesystem::path& path);

}  // namespace delmesh::test
