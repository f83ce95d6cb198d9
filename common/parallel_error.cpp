#include "common/parallel_error.hpp"

#include <array>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "common/error.hpp"

namespace xpl {

namespace {

constexpr std::array<std::string_view, static_cast<int>(ParallelSite::COUNT)> SITE_NAMES = {
    "none",           "element-forces", "element-boundary", "hex-stiffness", "contact-search",
    "contact-forces", "broad-phase",    "overclosure",      "clearance",     "solver-stop"};

struct FaultPoint {
  ParallelSite site = ParallelSite::None;
  Index index = 0;
};

/// XPL_TEST_FAULT=SITE:INDEX; nothing for an unset or malformed value.
FaultPoint fault_from_environment() {
  const char* value = std::getenv("XPL_TEST_FAULT");
  if (value == nullptr) return {};
  const std::string text = value;
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos) return {};
  char* end = nullptr;
  const long index = std::strtol(text.c_str() + colon + 1, &end, 10);
  if (end == text.c_str() + colon + 1 || *end != '\0' || index < 0) return {};
  for (int s = 1; s < static_cast<int>(ParallelSite::COUNT); ++s)
    if (SITE_NAMES[s] == std::string_view(text).substr(0, colon))
      return {static_cast<ParallelSite>(s), static_cast<Index>(index)};
  return {};
}

const FaultPoint FAULT = fault_from_environment();

}  // namespace

std::string_view parallel_site_name(ParallelSite site) {
  const int s = static_cast<int>(site);
  return s >= 0 && s < static_cast<int>(ParallelSite::COUNT) ? SITE_NAMES[s] : "?";
}

namespace fault_injection {

const ParallelSite SITE = FAULT.site;

void throw_at(ParallelSite site, Index index) {
  if (site == FAULT.site && index == FAULT.index)
    throw std::runtime_error("injected fault at " + std::string(parallel_site_name(site)) + ":" +
                             std::to_string(index) + " (XPL_TEST_FAULT)");
}

void stop_at(long increment, Real time) {
  if (FAULT.site == ParallelSite::SolverStop && increment == FAULT.index)
    throw SolverError(
        "injected stop at increment " + std::to_string(increment) + " (XPL_TEST_FAULT)", 0,
        increment, time);
}

}  // namespace fault_injection

void ParallelErrors::keep(Index index, std::exception_ptr error) noexcept {
  std::lock_guard<std::mutex> lock(m_mutex);
  if (!m_error || index < m_index) {
    m_error = std::move(error);
    m_index = index;
  }
}

}  // namespace xpl
