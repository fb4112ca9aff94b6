// The discarding log sink (see log.h).
#include "toolkit/core/log.h"

namespace delmesh {

namespace {
class NullLogSink final : public LogSink {
 public:
  void write(LogLevel, std::string_view) override {}
};
}  // namespace

LogSink& null_log_sink() {
  static NullLogSink sink;
  return sink;
}

}  // namespace delmesh
