#include "reports/provenance.h"

#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <ctime>
#include <random>

#include "git_revision.h"  // generated at build time

namespace locbench::reports {

const std::string& invocation_run_id() {
  static const std::string id = [] {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
    std::random_device entropy;
    return fmt::format("{}-{}-{:08x}", stamp, static_cast<long>(::getpid()), entropy());
  }();
  return id;
}

Provenance current_provenance(const std::string& command_line) {
  Provenance p;
  p.tool_version = LOCBENCH_VERSION;
  p.git_revision = LOCBENCH_GIT_REVISION;
#if defined(__clang__)
  p.compiler = std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  p.compiler = std::string("GCC ") + __VERSION__;
#else
  p.compiler = "unknown";
#endif
  p.compiler_flags = LOCBENCH_CXX_FLAGS;
  p.build_type = LOCBENCH_BUILD_TYPE;
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) == 0) p.host = host;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  p.utc_time = buf;
  p.command_line = command_line;
  p.run_id = invocation_run_id();
  return p;
}

}  // namespace locbench::reports
