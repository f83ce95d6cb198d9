#pragma once
/// \file The batched layout both hex formulations share (C3D8R in hex8r.*, C3D8 in hex8.*):
/// the elements coloured (no two elements of a colour share a node) and packed into batches of
/// simd::W lanes of one colour, their corner nodes and elastic constants per lane (AoSoA), the
/// per-batch reductions, and the partition of the one-region force pass (thread_partition.hpp).
/// A block owns one HexBatches and its own state arrays; the kernels stay in the blocks.

#include <omp.h>

#include <algorithm>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "elements/increment_limit.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/parallel/element_coloring.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/parallel/thread_partition.hpp"

namespace xpl::elements {

/// Hourglass control form of a C3D8R element: Flanagan–Belytschko's stiffness or viscous
/// form, or the enhanced assumed-strain stabilisation (hex8r_enhanced.hpp).
enum class HourglassForm { Stiffness, Viscous, Enhanced };

/// Extra factor on the stable increment of nearly incompressible one-point hexes: L_e/c_d is
/// not conservative there (measured limits on regular meshes, in units of L_e/c_d: 1.01 at
/// ν = 0, 0.99 at 0.3, 0.97 at 0.4, 0.90 at 0.45, 0.86 at 0.49; tests/solver/test_stability).
/// 1 up to ν = 0.3, then falling linearly by 0.55 per unit of ν (0.895 at ν = 0.49).
constexpr Real poisson_dt_factor(Real poisson) {
  return poisson <= 0.3 ? 1.0 : 1.0 - 0.55 * (poisson - 0.3);
}

/// Material and control constants of one hex element.
struct HexMaterial {
  Real density = 0.0;                                 ///< kg/m^3
  Real young = 0.0;                                   ///< Pa
  Real poisson = 0.0;                                 ///< -
  HourglassForm hourglass = HourglassForm::Enhanced;  ///< C3D8R only
  Real hourglass_scale = 1.0;                         ///< scales the coefficient of the chosen form
  /// J2 plasticity of the material, or nullptr for an elastic one. Not owned: read (and
  /// copied, once per distinct law) by the block's constructor only.
  const Plasticity* plastic = nullptr;
};

/// What one internal-force pass reports (sums are over the block, in a fixed order).
struct HexStepTotals : IncrementLimit {
  Real strain_energy_increment = 0.0;     ///< ΔALLSE, J
  Real hourglass_energy_increment = 0.0;  ///< ΔALLAE, J
  Real viscous_energy_increment = 0.0;    ///< ΔALLVD, J
  Real plastic_energy_increment = 0.0;    ///< ΔALLPD, J (½(σ_n + σ_{n+1}):Δεᵖ V, mid V)
};

/// Layout, constants and force-pass partition of a set of 8-node hexes.
class HexBatches {
 public:
  static constexpr int W = simd::W;
  /// Per-lane constants both formulations read; a block's own constants follow from
  /// N_SHARED on (the constructor's `n_constants` counts both).
  enum Constant { LAMBDA = 0, TWO_MU, DENSITY, WAVE_SPEED, DT_FACTOR, N_SHARED };

  HexBatches() = default;
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per element
  /// (Abaqus order); `materials`: one per element, whose elastic constants fill the shared
  /// constants; `n_constants` ≥ N_SHARED constants per lane. Padding lanes copy lane 0.
  /// `layout`: the batches to use (a distributed run's share of a whole model's layout, its
  /// lane owners numbered in `element_index`), or null: coloured and packed here.
  HexBatches(std::vector<Index> element_index, const std::vector<Index>& connectivity,
             const std::vector<HexMaterial>& materials, Index node_count, int n_constants,
             const BatchLayout* layout = nullptr);

  /// Number of elements.
  Index size() const { return static_cast<Index>(m_element_index.size()); }
  /// Number of batches (all colours).
  Index batch_count() const { return m_color_batches.back(); }
  /// Number of colours.
  int color_count() const { return static_cast<int>(m_color_batches.size()) - 1; }
  /// Batches of colour c: [color_batches()[c], color_batches()[c + 1]).
  const std::vector<Index>& color_batches() const { return m_color_batches; }
  /// Model index of block element i.
  Index element_index(Index i) const { return m_element_index[i]; }
  const std::vector<Index>& element_indices() const { return m_element_index; }
  /// Block element of lane l of batch b, or NO_INDEX for a padding lane.
  Index lane_owner(Index b, int l) const { return m_lane_owner[b * W + l]; }
  /// The block element whose values lane l of batch b computes (lane 0's for padding).
  Index lane_element(Index b, int l) const {
    const Index owner = m_lane_owner[b * W + l];
    return owner != NO_INDEX ? owner : m_lane_owner[b * W];
  }
  /// Slot (batch·W + lane) of block element i.
  Index slot(Index i) const { return m_slot[i]; }
  const std::vector<Index>& slots() const { return m_slot; }
  /// Block element of every lane ([b][W]), NO_INDEX for padding lanes.
  const std::vector<Index>& lane_owners() const { return m_lane_owner; }
  /// Corner nodes of batch b, [corner 8][W].
  const Index* conn(Index b) const { return &m_conn[static_cast<std::size_t>(b) * 8 * W]; }
  /// Constants of batch b, [constant][W].
  const Real* constants(Index b) const {
    return &m_const[static_cast<std::size_t>(b) * m_n_const * W];
  }
  Real* constants(Index b) { return &m_const[static_cast<std::size_t>(b) * m_n_const * W]; }

  /// Throws std::invalid_argument, naming `who`, unless a model-sized array of `size` values
  /// holds `per_element` values in the row of every element of the block (imported states).
  void check_model_rows(std::size_t size, int per_element, const char* who) const;

  /// Adds ρ V₀ / 8 to each node of each element (reference coordinates n_nodes × 3, m).
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass) const;

  /// Index into `laws` (copies of the distinct laws, in order of first use) of every lane, −1
  /// for elastic lanes, and whether each batch has a plastic lane; empty when no element is
  /// plastic (P2: an elastic block holds no plastic state).
  struct PlasticLanes {
    std::vector<Plasticity> laws;
    std::vector<int> lane_law;                 ///< [b][W]
    std::vector<unsigned char> batch_plastic;  ///< [b]
  };
  PlasticLanes plastic_lanes(const std::vector<HexMaterial>& materials) const;
  /// For an imported PEEQ array (model-sized, n_elements, -): checks its size, then calls
  /// `take(b, l, law, value)` for every lane whose `lane_law` is a law (padding lanes take lane
  /// 0's element, like its stress). A value that is not ≥ 0 throws std::invalid_argument,
  /// naming `who`.
  template <class Take>
  void for_imported_peeq(std::span<const Real> peeq, const std::vector<int>& lane_law,
                         const char* who, Take&& take) const;

  /// \name Partition of the force pass (thread_partition.hpp).
  /// Marks the nodes each of `parts` parts touches (mark_part_nodes()).
  void mark_nodes(int parts, std::vector<Index>& node_part) const;
  /// Takes the partition into `parts` parts whose boundary nodes (over every block of the
  /// pass) are `boundary`.
  void set_partition(int parts, const BoundaryNodes& boundary);
  /// Partition of these batches alone into `parts` parts, unless held already.
  void own_partition(int parts, Index node_count);
  /// Number of parts of the partition held (0: none yet).
  int parts() const { return m_parts; }
  /// The phase of each batch (in_phase(); empty: every batch of phase 0).
  void set_batch_phases(std::vector<unsigned char> phase) { m_batch_phase = std::move(phase); }
  /// Calls `batch(b, plastic)` for the batches of part `part`, colour after colour, with
  /// `plastic` std::true_type where `batch_plastic[b]` (empty: no plastic batch) says the
  /// batch has a plastic lane, else std::false_type (P2: elastic batches compile without any
  /// plasticity work).
  /// Only the batches of phase `phase` when `phase` ≥ 0 (in_phase(), set_batch_phases()).
  template <class ComputeBatch>
  void for_part_batches(int part, const std::vector<unsigned char>& batch_plastic, int phase,
                        ComputeBatch&& batch) const {
    for (int c = 0; c < color_count(); ++c) {
      const auto [first, last] = part_batches(m_color_batches, c, part, m_parts);
      for (Index b = first; b < last; ++b) {
        if (!in_phase(m_batch_phase, phase, b)) continue;
        if (!batch_plastic.empty() && batch_plastic[b])
          batch(b, std::true_type{});
        else
          batch(b, std::false_type{});
      }
    }
  }
  /// The force pass of the block alone: partitions it (own_partition()) into
  /// omp_get_max_threads() parts, runs `part(p)` for each in one parallel region and adds the
  /// exchanged forces of the boundary nodes into `force` (n_nodes × 3, N).
  template <class ComputePart>
  void own_pass(NodalVectors& force, ComputePart&& part);
  /// Adds the corner forces (N, [corner 8] per component) of the real lanes of batch b into
  /// `fx`, `fy`, `fz` (component arrays), lane by lane, except the corners at boundary nodes
  /// of the partition, which go to the exchange buffer.
  void scatter(Index b, const simd::Vec fnx[8], const simd::Vec fny[8], const simd::Vec fnz[8],
               Real* fx, Real* fy, Real* fz);
  /// As scatter(), every corner directly (passes that run colour by colour).
  void scatter_direct(Index b, const simd::Vec fnx[8], const simd::Vec fny[8],
                      const simd::Vec fnz[8], Real* fx, Real* fy, Real* fz) const;
  /// Adds the exchanged corner forces of boundary node k (rank), `node`, into `force`.
  void add_boundary_forces(Index k, Index node, NodalVectors& force) const {
    const Index n = static_cast<Index>(force.rows());
    Real* f = force.data() + node;
    for (Index s = m_exchange.first(k); s < m_exchange.first(k + 1); ++s) {
      f[0] += m_exchange_force[3 * s];
      f[n] += m_exchange_force[3 * s + 1];
      f[2 * n] += m_exchange_force[3 * s + 2];
    }
  }

  /// Calls `batch(b)` for every batch, colour by colour, the batches of a colour split between
  /// the threads (a barrier per colour: for passes that run rarely, as the stiffness product).
  template <class ComputeBatch>
  void for_color_batches(ParallelSite site, ComputeBatch&& batch) const;

  /// \name Increment limit of the last pass, per batch (reduced in batch order).
  /// Takes the element estimate `dt_e` of the real lanes of batch b, with `ok` false for lanes
  /// whose element turned over (the smallest model index of those is the failed element).
  void record_limit(Index b, const simd::Vec& dt_e, const bool ok[W]);
  /// Merges the limits of every batch into `limit`, in batch order.
  void merge_limits(IncrementLimit& limit) const;
  /// The limit of batch b as 3 values (dt, critical, failed; indices exact in doubles), and
  /// back (distributed runs: solver/distributed_run.hpp).
  void pack_limit(Index b, Real* out) const {
    out[0] = m_batch_dt[b];
    out[1] = static_cast<Real>(m_batch_critical[b]);
    out[2] = static_cast<Real>(m_batch_failed[b]);
  }
  void unpack_limit(Index b, const Real* in) {
    m_batch_dt[b] = in[0];
    m_batch_critical[b] = static_cast<Index>(in[1]);
    m_batch_failed[b] = static_cast<Index>(in[2]);
  }
  /// The corner slots of the boundary nodes of the partition held, and their values
  /// ([slot][3], N) after a force pass.
  const CornerExchange& corner_exchange() const { return m_exchange; }
  const std::vector<Real>& exchange_values() const { return m_exchange_force; }

 private:
  std::vector<Index> m_element_index;  ///< model index per block element
  std::vector<Index> m_conn;           ///< [b][node 8][W]
  std::vector<Index> m_lane_owner;     ///< [b][W] block element, or NO_INDEX for padding lanes
  std::vector<Real> m_const;           ///< [b][m_n_const][W]
  int m_n_const = N_SHARED;
  std::vector<Index> m_slot;  ///< block element -> batch·W + lane
  std::vector<Index> m_color_batches{0};
  std::vector<Real> m_batch_dt;
  std::vector<Index> m_batch_critical;
  std::vector<Index> m_batch_failed;
  int m_parts = 0;
  std::vector<unsigned char> m_batch_phase;  ///< [b] (in_phase()), or empty
  bool m_own_partition = false;              ///< built by own_partition() for the block alone
  CornerExchange m_exchange;
  std::vector<Real> m_exchange_force;   ///< [slot][3], N
  std::vector<Index> m_boundary_nodes;  ///< of the partition of the block alone
};

template <class ComputePart>
void HexBatches::own_pass(NodalVectors& force, ComputePart&& part) {
  const int parts = std::max(1, omp_get_max_threads());
  own_partition(parts, static_cast<Index>(force.rows()));
  partitioned_pass(parts, static_cast<Index>(m_boundary_nodes.size()), part,
                   [&](Index k) { add_boundary_forces(k, m_boundary_nodes[k], force); });
}

template <class Take>
void HexBatches::for_imported_peeq(std::span<const Real> peeq, const std::vector<int>& lane_law,
                                   const char* who, Take&& take) const {
  check_model_rows(peeq.size(), 1, who);
  for (Index b = 0; b < batch_count(); ++b)
    for (int l = 0; l < W; ++l) {
      const int law = lane_law[static_cast<std::size_t>(b) * W + l];
      if (law < 0) continue;
      const Index e = m_element_index[lane_element(b, l)];
      const Real value = peeq[static_cast<std::size_t>(e)];
      if (!(value >= 0.0)) {
        throw std::invalid_argument(std::string(who) + ": PEEQ of element " + std::to_string(e) +
                                    " is " + std::to_string(value) + "; expected a value >= 0");
      }
      take(b, l, law, value);
    }
}

template <class ComputeBatch>
void HexBatches::for_color_batches(ParallelSite site, ComputeBatch&& batch) const {
  for (int c = 0; c < color_count(); ++c) {
    const Index first = m_color_batches[c], last = m_color_batches[c + 1];
    ParallelErrors errors;
#pragma omp parallel for schedule(static) if (last - first >= simd::MIN_PARALLEL_BATCHES)
    for (Index b = first; b < last; ++b) errors.guard(site, b, [&] { batch(b); });
    errors.rethrow_if_any();
  }
}

}  // namespace xpl::elements
