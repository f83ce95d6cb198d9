// The output gathers of ElementSet (element_set.hpp): a frame's element fields all at once
// (gather_output, gathered to rank 0 in a distributed run) or one at a time (fill_output, the
// writer's pull in a one-process run, issue 38), and PEEQ.
#include <limits>

#include "solver/distributed_run.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/forces/element_set_blocks.hpp"

namespace xpl {

void ElementSet::gather_output(const State& state, const FrameRequest& what,
                               FrameFields& frame) const {
  gather_local_output(state, what, frame);
  if (m_run == nullptr) return;
  // Every element's row from its rank to rank 0, which writes.
  if (what.plastic_strain)
    for (std::vector<Real>* rows :
         {&frame.peeq, &frame.peeq_bottom, &frame.peeq_middle, &frame.peeq_top})
      m_run->gather_elements_to_root(*rows, 1);
  if (!what.stress && !what.volume && !what.thickness) return;
  m_run->gather_elements_to_root(frame.stress, 6);
  m_run->gather_elements_to_root(frame.volume, 1);
  m_run->gather_elements_to_root(frame.hourglass_state, elements::HOURGLASS_STATE_WIDTH);
  m_run->gather_elements_to_root(frame.stress_bottom, 6);
  m_run->gather_elements_to_root(frame.stress_top, 6);
  m_run->gather_elements_to_root(frame.thickness, 1);
}

void ElementSet::gather_plastic_strain(const FrameRequest& what, FrameFields& frame) const {
  if (what.plastic_strain) {
    // PEEQ of every element (0 where elastic); each block writes the rows of its elements.
    frame.peeq.assign(static_cast<std::size_t>(m_model.element_count()), 0.0);
    for_each_block([&](const auto& block) { block.gather_plastic_strain(frame.peeq); });
    if (m_model.has_plastic_shells()) {
      // Per section point: NaN rows for solids and rigid elements, like S_SNEG and S_SPOS.
      const auto n = static_cast<std::size_t>(m_model.element_count());
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      frame.peeq_bottom.assign(n, nan);
      frame.peeq_middle.assign(n, nan);
      frame.peeq_top.assign(n, nan);
      for_each_block([&](const auto& block) {
        if constexpr (requires {
                        block.gather_section_plastic_strain(frame.peeq_bottom, frame.peeq_middle,
                                                            frame.peeq_top);
                      })
          block.gather_section_plastic_strain(frame.peeq_bottom, frame.peeq_middle, frame.peeq_top);
      });
    }
  }
}

void ElementSet::gather_local_output(const State& state, const FrameRequest& what,
                                     FrameFields& frame) const {
  gather_plastic_strain(what, frame);
  if (!what.stress && !what.volume && !what.thickness) return;
  // Element output arrays exist only in runs that write element output (P2).
  const auto n_elements = static_cast<std::size_t>(m_model.element_count());
  frame.stress.resize(n_elements * 6, 0.0);
  frame.volume.resize(n_elements, 0.0);
  if (what.stress && has_hourglass_state()) {
    frame.hourglass_state.assign(n_elements * elements::HOURGLASS_STATE_WIDTH, 0.0);
    for_each_block([&](const auto& block) {
      if constexpr (requires { block.gather_hourglass_state(frame.hourglass_state); })
        block.gather_hourglass_state(frame.hourglass_state);
    });
  }
  if (has_shells()) {
    // Section output: NaN rows for the solids and rigid elements (P2: only on shell models;
    // in a distributed run on every rank, also one whose part holds no shell).
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    frame.stress_bottom.resize(n_elements * 6, nan);
    frame.stress_top.resize(n_elements * 6, nan);
    frame.thickness.resize(n_elements, nan);
  }
  const elements::OutputArrays out{state.position,      frame.stress,     frame.volume,
                                   frame.stress_bottom, frame.stress_top, frame.thickness};
  for_each_block([&](const auto& block) { block.gather_output(out); });
}

void ElementSet::fill_output(const State& state, ElementField field,
                             std::vector<Real>& rows) const {
  // The values of gather_local_output: the same initial rows (0 or NaN where no block writes)
  // and each block writing its elements' rows of this field only (the other arrays empty).
  const auto n_elements = static_cast<std::size_t>(m_model.element_count());
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  if (field == ElementField::HourglassState) {
    rows.clear();
    if (!has_hourglass_state()) return;
    rows.assign(n_elements * elements::HOURGLASS_STATE_WIDTH, 0.0);
    for_each_block([&](const auto& block) {
      if constexpr (requires { block.gather_hourglass_state(rows); })
        block.gather_hourglass_state(rows);
    });
    return;
  }
  std::vector<Real> none;
  const auto pick = [&](ElementField f) -> std::vector<Real>& { return f == field ? rows : none; };
  switch (field) {
    case ElementField::Stress:
      rows.assign(n_elements * 6, 0.0);
      break;
    case ElementField::Volume:
      rows.assign(n_elements, 0.0);
      break;
    case ElementField::StressBottom:
    case ElementField::StressTop:
      if (has_shells())
        rows.assign(n_elements * 6, nan);
      else
        rows.clear();
      break;
    case ElementField::Thickness:
      if (has_shells())
        rows.assign(n_elements, nan);
      else
        rows.clear();
      break;
    case ElementField::HourglassState:
      break;
  }
  if (rows.empty()) return;
  const elements::OutputArrays out{state.position,
                                   pick(ElementField::Stress),
                                   pick(ElementField::Volume),
                                   pick(ElementField::StressBottom),
                                   pick(ElementField::StressTop),
                                   pick(ElementField::Thickness)};
  for_each_block([&](const auto& block) { block.gather_output(out); });
}

}  // namespace xpl
