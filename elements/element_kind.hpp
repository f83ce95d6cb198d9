#pragma once
/// \file What every element kind provides: a block of the elements of one type (the C3D8R and
/// C3D8 blocks in hex/, the S4R block in shell/) behind one C++20 concept, so that the solver
/// (solver/forces/element_set.*) folds over the kinds at compile time, with no branch per type and
/// no virtual call: each kind's force pass stays its own SIMD kernel.
///
/// A kind is a class K with
///   - K::NAME (the Abaqus type, "C3D8R"), K::NODES (nodes per element), K::Properties (the
///     material and section constants of one element, from the model:
///     solver/forces/element_kinds.*) and K::Totals (what a force pass reports: ΔALLSE,
///     ΔALLAE and the increment limit, and ΔALLVD, ΔALLPD where the kind has them);
///   - a constructor K(model indices, connectivity (NODES per element), properties, node count);
///   - the force pass in parts (thread_partition.hpp): mark_nodes, set_partition,
///     set_batch_phases, forces_of_part(part, ForcePass), add_boundary_forces(k, node,
///     ForcePass), add_totals;
///   - output and imported state: gather_output(OutputArrays), gather_plastic_strain,
///     set_stress (middle, bottom and top section rows; solids read the middle ones);
///   - the lumped mass of the block (add_lumped_mass) and, per element in the reference
///     configuration, its mass share per node (K::node_mass) and its stable increment at rest
///     (K::stable_increment): the one formula of the kind that *FIXED MASS SCALING and
///     *DLOAD GRAV (solver/increment/mass_scaling.*, solver/loads/gravity_loads.*) use too.
/// Optional members, found by `requires` where they are used: rotational DOFs
/// (K::ROTATIONS), hourglass state (gather_hourglass_state / set_hourglass_state), the
/// linear stiffness product of the global estimate (add_stiffness_product), section output
/// (gather_section_plastic_strain). docs/dev/extending.md says how to add a kind.

#include <concepts>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/increment_limit.hpp"
#include "elements/parallel/thread_partition.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

/// The nodal arrays of one internal-force pass (n_nodes × 3 each).
struct ForcePass {
  const NodalVectors& position;       ///< x_{n+1}, m
  const NodalVectors& velocity_half;  ///< v_{n+1/2}, m/s
  /// ω_{n+1/2}, rad/s (0 rows on models without rotational DOFs)
  const NodalVectors& angular_velocity_half;
  Real dt = 0.0;              ///< t_{n+1} − t_n, s (0: no rate terms)
  Real bulk_linear = 0.0;     ///< bulk viscosity b1 of the step
  Real bulk_quadratic = 0.0;  ///< bulk viscosity b2 of the step
  NodalVectors& force;        ///< internal forces, added into, N
  NodalVectors& moment;       ///< internal moments, added into, N·m (0 rows without rotations)
  /// The batches computed: every one (−1), or those of one phase (in_phase(), a block's
  /// set_batch_phases()).
  int phase = -1;
};

/// Element output arrays, model-sized rows (row e·6.. for stresses); a kind writes the rows
/// of its elements. The section arrays (bottom, top, thickness) are sized only on models
/// with a kind that writes them. An empty array is not asked for: a kind leaves it alone (a
/// frame written field by field asks for one array at a time, ElementSet::fill_output).
struct OutputArrays {
  const NodalVectors& position;      ///< configuration of the output, m
  std::vector<Real>& stress;         ///< S, middle section point for shells, Pa
  std::vector<Real>& volume;         ///< EVOL, m³
  std::vector<Real>& stress_bottom;  ///< S at SNEG, Pa
  std::vector<Real>& stress_top;     ///< S at SPOS, Pa
  std::vector<Real>& thickness;      ///< STH, m
};

/// An element kind (see the file comment).
template <class K>
concept ElementKind = requires(K& k, const K& c, int parts, Index i, std::vector<Index>& node_part,
                               const BoundaryNodes& boundary, const ForcePass& pass,
                               typename K::Totals& totals, const OutputArrays& out,
                               std::vector<Real>& rows, std::span<const Real> in,
                               const NodalVectors& reference,
                               const typename K::Properties& properties, const V3<Real>* corners) {
  { K::NAME } -> std::convertible_to<const char*>;
  { K::SETUP_NOTE } -> std::convertible_to<const char*>;
  { K::NODES } -> std::convertible_to<int>;
  requires std::derived_from<typename K::Totals, IncrementLimit>;
  { c.size() } -> std::same_as<Index>;
  { c.color_count() } -> std::same_as<int>;
  { c.element_index(i) } -> std::same_as<Index>;
  c.mark_nodes(parts, node_part);
  k.set_partition(parts, boundary);
  k.set_batch_phases(std::vector<unsigned char>{});
  k.forces_of_part(parts, pass);
  c.add_boundary_forces(i, i, pass);
  c.add_totals(totals);
  c.gather_output(out);
  c.gather_plastic_strain(rows);
  k.set_stress(reference, in, in, in);
  c.add_lumped_mass(reference, rows, rows);
  { K::node_mass(properties, corners) } -> std::same_as<Real>;
  { K::stable_increment(properties, corners, Real{}) } -> std::same_as<Real>;
};

}  // namespace xpl::elements
