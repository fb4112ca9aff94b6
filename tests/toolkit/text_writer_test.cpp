// TextWriter (toolkit/io): numbers are formatted straight into the write buffer, so the
// file must hold exactly what std::to_chars gives for each value, also where a number
// lands at the end of the 64 KiB buffer and the buffer is flushed before it.
#include <gtest/gtest.h>

#include <charconv>
#include <cstdint>
#include <limits>
#include <string>

#include "tests/support/scratch_dir.h"
#include "toolkit/io/text_writer.h"

namespace delmesh {
namespace {

template <class Number>
std::string chars(Number value) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

TEST(TextWriter, NumbersAcrossBufferFlushesReadAsToChars) {
  const test::ScratchDir dir("text-writer");
  std::string expected;
  {
    TextWriter out(dir / "numbers.txt");
    // Lines of varying length: numbers end at every offset of the buffer.
    for (std::int64_t i = 0; i < 40000; ++i) {
      const std::int64_t integer = (i % 7 == 0 ? -1 : 1) * i * i * 7919;
      const std::uint64_t unsigned_value = std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(i);
      const double real = (i % 3 == 0 ? -1.0 : 1.0) / (1.0 + static_cast<double>(i)) * (i % 5 == 0 ? 1e300 : 1e-300);
      const std::uint32_t small = static_cast<std::uint32_t>(i);
      out.line(integer, unsigned_value, real, small);
      out.put('x');
      out.put(std::string_view(i % 2 == 0 ? "" : "ab"));
      expected += chars(integer) + ' ' + chars(unsigned_value) + ' ' + chars(real) + ' ' +
                  chars(static_cast<std::int64_t>(small)) + "\nx" + (i % 2 == 0 ? "" : "ab");
    }
    out.put(std::numeric_limits<double>::lowest()).put(' ').put(std::numeric_limits<std::int64_t>::min());
    expected += chars(std::numeric_limits<double>::lowest()) + ' ' + chars(std::numeric_limits<std::int64_t>::min());
    ASSERT_TRUE(out.finish());
  }
  EXPECT_GT(expected.size(), std::size_t{3} << 16);
  EXPECT_EQ(test::read_file(dir / "numbers.txt"), expected);
}

}  // namespace
}  // namespace delmesh
