#pragma once
/// \file Copies of per-element state between a block's batched (AoSoA) arrays and model-sized
/// rows: what `--import` needs for state the result file holds as opaque rows (the
/// accumulated hourglass resultants of C3D8R and S4R, HOURGLASS_STATE_WIDTH values per
/// element).

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace xpl::elements {

/// Values per element row of the hourglass state in a result file (the widest block's: the
/// C3D8R's 4 modes × 3 components; the S4R uses the first 9, see Shell4rBlock).
inline constexpr int HOURGLASS_STATE_WIDTH = 12;

/// Writes `count` values per element of `batched` ([b][count][W], lane l of batch b at slot
/// b·W + l) into the model rows `rows` (n_elements × HOURGLASS_STATE_WIDTH): row e of block
/// element i is the model index element_index[i], its slot slot[i].
inline void gather_lane_rows(const std::vector<Real>& batched, int count, int lanes,
                             const std::vector<Index>& element_index,
                             const std::vector<Index>& slot, std::vector<Real>& rows) {
  const auto width = static_cast<std::size_t>(HOURGLASS_STATE_WIDTH);
  for (std::size_t i = 0; i < element_index.size(); ++i) {
    const auto s = static_cast<std::size_t>(slot[i]);
    const std::size_t b = s / lanes, l = s % lanes;
    const std::size_t e = static_cast<std::size_t>(element_index[i]);
    for (int k = 0; k < count; ++k) rows[e * width + k] = batched[(b * count + k) * lanes + l];
  }
}

/// The inverse of gather_lane_rows; padding lanes (lane_owner NO_INDEX) get lane 0's values,
/// as they compute a copy of it. Throws std::invalid_argument if `rows` is not model-sized.
inline void set_lane_rows(std::span<const Real> rows, int count, int lanes,
                          const std::vector<Index>& element_index, const std::vector<Index>& slot,
                          const std::vector<Index>& lane_owner, std::vector<Real>& batched) {
  const auto width = static_cast<std::size_t>(HOURGLASS_STATE_WIDTH);
  for (Index e : element_index)
    if ((static_cast<std::size_t>(e) + 1) * width > rows.size())
      throw std::invalid_argument("set_lane_rows: " + std::to_string(rows.size()) +
                                  " values do not reach the row of element " + std::to_string(e) +
                                  "; expected n_elements × " + std::to_string(width));
  for (std::size_t i = 0; i < element_index.size(); ++i) {
    const auto s = static_cast<std::size_t>(slot[i]);
    const std::size_t b = s / lanes, l = s % lanes;
    const std::size_t e = static_cast<std::size_t>(element_index[i]);
    for (int k = 0; k < count; ++k) batched[(b * count + k) * lanes + l] = rows[e * width + k];
  }
  const std::size_t batches = lane_owner.size() / lanes;
  for (std::size_t b = 0; b < batches; ++b)
    for (int l = 1; l < lanes; ++l) {
      if (lane_owner[b * lanes + l] != NO_INDEX) continue;
      for (int k = 0; k < count; ++k)
        batched[(b * count + k) * lanes + l] = batched[(b * count + k) * lanes];
    }
}

}  // namespace xpl::elements
