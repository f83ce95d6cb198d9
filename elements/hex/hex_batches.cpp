#include "elements/hex/hex_batches.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex_block.hpp"
#include "elements/parallel/element_coloring.hpp"

namespace xpl::elements {

HexBatches::HexBatches(std::vector<Index> element_index, const std::vector<Index>& connectivity,
                       const std::vector<HexMaterial>& materials, Index node_count, int n_constants,
                       const BatchLayout* given)
    : m_element_index(std::move(element_index)), m_n_const(n_constants) {
  BatchLayout layout = given != nullptr ? *given : make_batches(connectivity, 8, node_count, W);
  m_color_batches = std::move(layout.color_batches);
  m_lane_owner = std::move(layout.lane_owner);
  const auto nb = static_cast<std::size_t>(batch_count());
  m_conn.assign(nb * 8 * W, 0);
  m_const.assign(nb * m_n_const * W, 0.0);
  m_slot.assign(static_cast<std::size_t>(size()), NO_INDEX);
  m_batch_dt.assign(nb, 0.0);
  m_batch_critical.assign(nb, NO_INDEX);
  m_batch_failed.assign(nb, NO_INDEX);
  for (Index b = 0; b < batch_count(); ++b)
    for (int l = 0; l < W; ++l) {
      const Index owner = m_lane_owner[b * W + l];
      // Padding lanes compute a copy of lane 0 and are masked out of every result.
      const Index e = lane_element(b, l);
      if (owner != NO_INDEX) m_slot[owner] = b * W + l;
      for (int a = 0; a < 8; ++a) m_conn[(b * 8 + a) * W + l] = connectivity[e * 8 + a];
      const HexMaterial& m = materials[e];
      const Real mu = m.young / (2.0 * (1.0 + m.poisson));
      const Real lambda = m.young * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
      Real* c = constants(b) + l;
      c[LAMBDA * W] = lambda;
      c[TWO_MU * W] = 2.0 * mu;
      c[DENSITY * W] = m.density;
      c[WAVE_SPEED * W] = hex_wave_speed(m);
      // The selectively reduced hex's regular-mesh limits lie within 1 % of the one-point
      // hex's (highest mode of a 6×6×6 mesh: 0.974, 0.889, 0.859 L_e/c_d at ν = 0.3, 0.45,
      // 0.49 against 0.978, 0.892, 0.860), so both take this estimate; the global estimate
      // covers the meshes with few neighbours (tests/solver/test_stability*.cpp).
      c[DT_FACTOR * W] = poisson_dt_factor(m.poisson);
    }
}

void HexBatches::check_model_rows(std::size_t size, int per_element, const char* who) const {
  const auto k = static_cast<std::size_t>(per_element);
  for (Index e : m_element_index)
    if (static_cast<std::size_t>(e) * k + k > size) {
      throw std::invalid_argument(std::string(who) + ": " + std::to_string(size) +
                                  " values do not reach the row of element " + std::to_string(e) +
                                  "; expected n_elements" +
                                  (k > 1 ? " × " + std::to_string(k) : std::string()));
    }
}

void HexBatches::add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass) const {
  for (Index b = 0; b < batch_count(); ++b)
    for (int l = 0; l < W; ++l) {
      if (m_lane_owner[b * W + l] == NO_INDEX) continue;
      Real x[8], y[8], z[8];
      const Index* corners = conn(b);
      for (int a = 0; a < 8; ++a) {
        const Index node = corners[a * W + l];
        x[a] = reference(node, 0);
        y[a] = reference(node, 1);
        z[a] = reference(node, 2);
      }
      const Real share = hex_node_mass(constants(b)[DENSITY * W + l], x, y, z);
      for (int a = 0; a < 8; ++a) mass[corners[a * W + l]] += share;
    }
}

HexBatches::PlasticLanes HexBatches::plastic_lanes(
    const std::vector<HexMaterial>& materials) const {
  PlasticLanes p;
  // One copy of each distinct law (materials point into the model's materials).
  std::vector<const Plasticity*> seen;
  std::vector<int> law_of_element(materials.size(), -1);
  for (std::size_t e = 0; e < materials.size(); ++e) {
    const Plasticity* law = materials[e].plastic;
    if (law == nullptr) continue;
    std::size_t k = 0;
    while (k < seen.size() && seen[k] != law) ++k;
    if (k == seen.size()) {
      seen.push_back(law);
      p.laws.push_back(*law);
    }
    law_of_element[e] = static_cast<int>(k);
  }
  if (p.laws.empty()) return p;
  p.lane_law.assign(static_cast<std::size_t>(batch_count()) * W, -1);
  p.batch_plastic.assign(static_cast<std::size_t>(batch_count()), 0);
  for (Index b = 0; b < batch_count(); ++b)
    for (int l = 0; l < W; ++l) {
      // Padding lanes follow lane 0, whose copy they compute.
      const int law = law_of_element[static_cast<std::size_t>(lane_element(b, l))];
      if (law < 0) continue;
      p.lane_law[b * W + l] = law;
      if (m_lane_owner[b * W + l] != NO_INDEX) p.batch_plastic[b] = 1;
    }
  return p;
}

void HexBatches::mark_nodes(int parts, std::vector<Index>& node_part) const {
  mark_part_nodes(m_conn, m_lane_owner, m_color_batches, 8, W, parts, node_part);
}

void HexBatches::set_partition(int parts, const BoundaryNodes& boundary) {
  m_parts = parts;
  m_own_partition = false;
  m_exchange = CornerExchange(m_conn, m_lane_owner, 8, W, boundary);
  m_exchange_force.assign(static_cast<std::size_t>(m_exchange.size()) * 3, 0.0);
}

void HexBatches::own_partition(int parts, Index node_count) {
  if (m_own_partition && m_parts == parts) return;
  std::vector<Index> node_part(node_count, UNTOUCHED);
  mark_nodes(parts, node_part);
  const BoundaryNodes boundary = boundary_nodes(node_part);
  set_partition(parts, boundary);
  m_boundary_nodes = boundary.nodes;
  m_own_partition = true;
}

void HexBatches::scatter(Index b, const simd::Vec fnx[8], const simd::Vec fny[8],
                         const simd::Vec fnz[8], Real* fx, Real* fy, Real* fz) {
  const Index* slots = m_exchange.batch_slots(b);
  if (slots == nullptr) {
    scatter_direct(b, fnx, fny, fnz, fx, fy, fz);
    return;
  }
  const Index* corners = conn(b);
  for (int l = 0; l < W; ++l) {
    if (m_lane_owner[b * W + l] == NO_INDEX) continue;
    for (int a = 0; a < 8; ++a) {
      // A node another thread also writes: to the exchange buffer, summed after the pass.
      if (const Index s = slots[a * W + l]; s != NO_INDEX) {
        Real* e = &m_exchange_force[3 * static_cast<std::size_t>(s)];
        e[0] = fnx[a][l];
        e[1] = fny[a][l];
        e[2] = fnz[a][l];
        continue;
      }
      const Index node = corners[a * W + l];
      fx[node] += fnx[a][l];
      fy[node] += fny[a][l];
      fz[node] += fnz[a][l];
    }
  }
}

void HexBatches::scatter_direct(Index b, const simd::Vec fnx[8], const simd::Vec fny[8],
                                const simd::Vec fnz[8], Real* fx, Real* fy, Real* fz) const {
  const Index* corners = conn(b);
  for (int l = 0; l < W; ++l) {
    if (m_lane_owner[b * W + l] == NO_INDEX) continue;
    for (int a = 0; a < 8; ++a) {
      const Index node = corners[a * W + l];
      fx[node] += fnx[a][l];
      fy[node] += fny[a][l];
      fz[node] += fnz[a][l];
    }
  }
}

void HexBatches::record_limit(Index b, const simd::Vec& dt_e, const bool ok[W]) {
  Real best_dt = std::numeric_limits<Real>::infinity();
  Index critical = NO_INDEX, failed = NO_INDEX;
  for (int l = 0; l < W; ++l) {
    const Index owner = m_lane_owner[b * W + l];
    if (owner == NO_INDEX) continue;
    const Index model_e = m_element_index[owner];
    if (!ok[l]) {
      if (failed == NO_INDEX || model_e < failed) failed = model_e;
    } else if (dt_e[l] < best_dt || (dt_e[l] == best_dt && model_e < critical)) {
      best_dt = dt_e[l];
      critical = model_e;
    }
  }
  m_batch_dt[b] = best_dt;
  m_batch_critical[b] = critical;
  m_batch_failed[b] = failed;
}

void HexBatches::merge_limits(IncrementLimit& limit) const {
  for (Index b = 0; b < batch_count(); ++b)
    limit.merge(m_batch_dt[b], m_batch_critical[b], m_batch_failed[b]);
}

}  // namespace xpl::elements
