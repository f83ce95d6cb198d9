#pragma once
/// \file The fields only output needs: element stresses, volumes, thicknesses, PEEQ, the
/// hourglass state for --import and the contact output per node. The OutputDriver owns them
/// and fills them before each field frame (ElementSet::gather_output, ContactStage::fill_output),
/// or lets the writer pull the element fields one at a time from the element blocks
/// (ElementFieldSource); the time loop never reads them.

#include <utility>
#include <vector>

#include "common/types.hpp"
#include "elements/lane_state.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// An element field of a frame that a writer can ask for on its own (FrameFields::element_rows).
enum class ElementField { Stress, StressBottom, StressTop, Thickness, Volume, HourglassState };

/// Fills the element fields of a frame on request, one at a time, from the solution: a writer
/// that takes them in turn into one buffer holds one field of the frame at a time instead of
/// all of them (six fields, 304 bytes per S4R element, issue 38).
class ElementFieldSource {
 public:
  virtual ~ElementFieldSource() = default;
  /// Fills `rows` with `field` of every element, sized and laid out as the FrameFields member
  /// of the same name (stress, stress_bottom, stress_top, thickness, volume, hourglass_state);
  /// empty where the frame would leave that member empty (no shells, no hourglass state).
  virtual void fill(ElementField field, std::vector<Real>& rows) const = 0;
};

/// The rows one rank writes of a frame in a run distributed over MPI ranks whose ranks write
/// JOB.h5 together (parallel HDF5, issue 37 item 5): runs [first, first + count) of node rows
/// (the nodes the rank owns; rank 0 also every node no other rank owns) and of element rows
/// (the rank's elements; rank 0 also every element of no rank, e.g. of rigid bodies). Every
/// row is written by exactly one rank. Not `collective`: one process writes every row.
struct FrameRows {
  bool collective = false;
  std::vector<std::pair<Index, Index>> nodes, elements;
};

/// The output-only fields of a field frame. Element fields: rows in the model's element order;
/// node fields: rows in the model's node order.
struct FrameFields {
  /// Width of a row of `hourglass_state` (values per element).
  static constexpr int HOURGLASS_WIDTH = elements::HOURGLASS_STATE_WIDTH;

  /// Cauchy stress per element, filled before each field frame (n_elements × 6, row-major,
  /// Abaqus order S11 S22 S33 S12 S13 S23), Pa. Solids: global axes. Shells: the middle
  /// section point, in the shell's local axes (Abaqus default: local 1 = projection of the
  /// global x axis on the shell, local 2 = n × 1), S33 = 0, S13/S23 = transverse shear.
  std::vector<Real> stress;
  /// Shell section stresses at the bottom (SNEG) and top (SPOS) section points, same layout
  /// as `stress`; rows of non-shell elements are NaN. Empty unless the model has shells.
  std::vector<Real> stress_bottom, stress_top;
  /// Current shell thickness STH (n_elements), m; NaN for non-shell elements. Empty unless
  /// the model has shells.
  std::vector<Real> thickness;
  /// Current element volume, filled with `stress` (n_elements), m^3.
  std::vector<Real> volume;
  /// Accumulated hourglass resultants (n_elements × HOURGLASS_WIDTH, each block's own layout:
  /// Hex8rBlock/Shell4rBlock::gather_hourglass_state; 0 for elements without), filled with
  /// `stress` on models with C3D8R or S4R elements, else empty: the state --import needs to
  /// continue a run with the same hourglass forces.
  std::vector<Real> hourglass_state;
  /// Equivalent plastic strain PEEQ (n_elements), -: 0 for elastic elements; shells: the
  /// largest of their section points. Filled before a frame that asks for it (plastic models).
  std::vector<Real> peeq;
  /// Shell PEEQ at the bottom (SNEG), middle and top (SPOS) section points (n_elements each),
  /// -: 0 for elastic shells, NaN for non-shell elements. Filled with `peeq` on models with
  /// plastic shells only, else empty.
  std::vector<Real> peeq_bottom, peeq_middle, peeq_top;

  // Contact output per node, filled before a frame that asks for it (zero away from contact).
  // The node's total contact force F (as slave and as face corner) split along its outward
  // normal n: CNORMF = (F·n) n, CSHEARF = F − CNORMF; CPRESS = −F·n / A and CSHEAR =
  // CSHEARF / A with A the tributary area (|F·n| / A on double-sided shell nodes).
  std::vector<Real> contact_pressure;  ///< CPRESS (n_nodes), Pa
  NodalVectors contact_shear;          ///< CSHEAR (n_nodes × 3), Pa
  std::vector<Real> contact_status;    ///< CSTATUS (n_nodes): 0 open, 1 slipping, 2 sticking
  NodalVectors contact_normal_force;   ///< CNORMF (n_nodes × 3), N
  NodalVectors contact_shear_force;    ///< CSHEARF (n_nodes × 3), N

  /// Which rows of each dataset this process writes (FrameRows).
  FrameRows rows;

  /// When set, the element fields stress, stress_bottom, stress_top, thickness, volume and
  /// hourglass_state are not held (empty) and come from `source` on request; the writer reads
  /// them through element_rows either way.
  const ElementFieldSource* source = nullptr;

  /// The rows of `field`: the member of that name, or, with a `source`, `buffer` filled from
  /// it (the member is then empty).
  const std::vector<Real>& element_rows(ElementField field, std::vector<Real>& buffer) const;
};

/// The copy of the stress rows `rows` (n_elements × 6, Abaqus order: `stress`, `stress_bottom`
/// or `stress_top` of a frame) that the XDMF file shows, into `global` (resized to n_elements ×
/// 6): global axes (each shell's row turned out of its local axes, elements::quad_frame of its
/// corners at `position`), VTK order. The writer fills it one tensor at a time, just before
/// writing it, into one buffer: three global copies kept with the frame cost 144 bytes per
/// element at the run's peak (issue 38).
void global_axis_rows(const Model& model, const NodalVectors& position,
                      const std::vector<Real>& rows, std::vector<Real>& global);

/// Component order of the XDMF copies of a tensor: VTK's Tensor6 (XX YY ZZ XY YZ XZ), i.e.
/// the Abaqus rows S11 S22 S33 S12 S23 S13.
inline constexpr int VTK_ORDER[6] = {0, 1, 2, 3, 5, 4};

/// One stress row (Abaqus order) in VTK order.
inline void to_vtk(const Real* abaqus, Real* vtk) {
  for (int c = 0; c < 6; ++c) vtk[c] = abaqus[VTK_ORDER[c]];
}

}  // namespace xpl
