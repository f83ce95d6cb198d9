#include "contact/penalty_increment.hpp"

#include <cmath>

#include "contact/contact_options.hpp"

namespace xpl::contact {

Real PenaltyLimit::stable_dt() const {
  if (!(omega_sq > 0.0)) return std::numeric_limits<Real>::infinity();
  return std::sqrt(PENALTY_INCREMENT_BUDGET / omega_sq);
}

void PenaltyStiffnessSum::reset(Index n_nodes) {
  const auto n = static_cast<std::size_t>(n_nodes);
  if (m_row.size() != n) {
    m_row.assign(n, 0.0);
    m_largest.assign(n, 0.0);
    m_interaction.assign(n, NO_INDEX);
    m_touched.clear();
    return;
  }
  for (Index i : m_touched) {
    m_row[i] = 0.0;
    m_largest[i] = 0.0;
    m_interaction[i] = NO_INDEX;
  }
  m_touched.clear();
}

void PenaltyStiffnessSum::add_row(Index node, Real value, Index interaction) {
  if (!(value > 0.0)) return;
  if (m_row[node] == 0.0) m_touched.push_back(node);
  m_row[node] += value;
  if (value > m_largest[node]) {
    m_largest[node] = value;
    m_interaction[node] = interaction;
  }
}

void PenaltyStiffnessSum::add_spring(Index slave_node, const std::array<Index, 4>& corners,
                                     const std::array<Real, 4>& weights, Real k, Index interaction,
                                     std::span<const Real> inverse_mass) {
  if (!(k > 0.0)) return;
  // 1 + Σ|N_J| over the corners that move (a rigid corner's column drops out of M⁻¹K).
  Real moving = 0.0;
  for (int a = 0; a < 4; ++a)
    if (inverse_mass[corners[a]] > 0.0) moving += std::abs(weights[a]);
  const Real span = k * (1.0 + moving);
  add_row(slave_node, span, interaction);
  for (int a = 0; a < 4; ++a)
    if (inverse_mass[corners[a]] > 0.0)
      add_row(corners[a], span * std::abs(weights[a]), interaction);
}

PenaltyLimit PenaltyStiffnessSum::largest(std::span<const Real> inverse_mass) const {
  PenaltyLimit out;
  for (Index i : m_touched) {
    const Real w = m_row[i] * inverse_mass[i];
    if (w > out.omega_sq || (w == out.omega_sq && out.node != NO_INDEX && i < out.node)) {
      out.omega_sq = w;
      out.node = i;
      out.interaction = m_interaction[i];
    }
  }
  return out;
}

}  // namespace xpl::contact
