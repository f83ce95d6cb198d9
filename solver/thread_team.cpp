#include "solver/thread_team.hpp"

#include <algorithm>

namespace xpl {

int team_size(const Model& model, int requested, int default_threads) {
  if (requested > 0) return requested;
  if (model.element_count() < SMALL_MODEL_ELEMENTS) return 1;
  return std::max(1, default_threads);
}

}  // namespace xpl
