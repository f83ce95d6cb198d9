#pragma once
/// \file The contact domain as a list of quadrilateral facets (stage 1 of the contact pipeline).
///
/// A contact face is four corner nodes ordered so that the right-hand normal
/// (x2 − x0) × (x3 − x1) points away from the material, out of the body it bounds. Solid faces
/// are the exterior faces of the hexes (a face shared by two hexes is interior). Every shell
/// gives two faces: SPOS with the shell normal n = (x3 − x1) × (x4 − x2) and the element's
/// corner order, SNEG with −n and the corner order reversed. A shell face's contact surface is
/// the mid-surface moved by half the node thickness along the face normal, so SPOS lies at
/// +t/2·n and SNEG at −t/2·n: both sides move outward along their own normal, which is why one
/// flag (`shell`) suffices.

#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "common/types.hpp"

namespace xpl::contact {

/// A point or direction in space, m.
using Vec3 = Eigen::Matrix<Real, 3, 1>;

/// What an element contributes to the contact domain.
enum class ElementKind : std::uint8_t {
  Other,  ///< no contact faces (point masses, unsupported types)
  Hex,    ///< 8-node hexahedron, Abaqus node order, faces S1..S6
  Shell,  ///< 4-node shell, faces SNEG and SPOS
};

/// Corner nodes (element node positions) of hex faces S1..S6; the right-hand normal of each
/// cycle points INTO the element (Abaqus face numbering).
inline constexpr int HEX_FACE_CORNERS[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                               {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
/// The hex face opposite each face S1..S6 (0..5).
inline constexpr int OPPOSITE_HEX_FACE[6] = {1, 0, 4, 5, 2, 3};
/// Face numbers of a shell element (those of the deck's `*SURFACE` SNEG / SPOS).
inline constexpr std::uint8_t SHELL_SNEG = 0;
inline constexpr std::uint8_t SHELL_SPOS = 1;

/// Element connectivity in compressed-row form, as the model stores it (no copy).
struct ElementTopology {
  std::span<const Index> offsets;      ///< (n_elements + 1) into `nodes`
  std::span<const Index> nodes;        ///< node indices, Abaqus element node order
  std::span<const ElementKind> kinds;  ///< (n_elements)
  Index element_count() const { return static_cast<Index>(kinds.size()); }
};

/// One face of a `*SURFACE, TYPE=ELEMENT`: hex S1..S6 = 0..5, shell SNEG = 0, SPOS = 1.
struct FaceRef {
  Index element = NO_INDEX;
  std::uint8_t face = 0;
};

/// One facet of the contact domain.
struct ContactFace {
  /// Corner node indices; (x2 − x0) × (x3 − x1) points out of the material.
  std::array<Index, 4> nodes{NO_INDEX, NO_INDEX, NO_INDEX, NO_INDEX};
  Index element = NO_INDEX;  ///< owning element (index into the topology)
  Index surface = NO_INDEX;  ///< surface id given by the caller (NO_INDEX: all exterior)
  std::uint8_t face = 0;     ///< face number as in FaceRef
  /// Shell face: its contact surface is the mid-surface moved by half the node thickness
  /// along the face normal (outward, for SPOS and SNEG alike).
  bool shell = false;
  /// Hex face: the element's four other nodes (those of the opposite face), which may never
  /// touch this face: a node of the element lies on the element's own boundary, and a face
  /// of its own element is "behind" it only because the element is squashed (NO_INDEX for a
  /// shell face).
  std::array<Index, 4> back{NO_INDEX, NO_INDEX, NO_INDEX, NO_INDEX};
  /// Whether `node` is one of the element's nodes that are not corners of this face.
  bool behind(Index node) const {
    return back[0] == node || back[1] == node || back[2] == node || back[3] == node;
  }
};

/// Exterior faces of the hexes (outward corner order, each once) followed by both sides of
/// every shell (SNEG then SPOS), in element order; every face carries `surface`.
std::vector<ContactFace> exterior_faces(const ElementTopology& topology, Index surface = NO_INDEX);

/// The faces of a `*SURFACE, TYPE=ELEMENT` (each FaceRef in order) tagged with `surface`.
/// Throws std::invalid_argument for an element without contact faces or a face number out
/// of range for its kind (the deck reader has checked both already).
std::vector<ContactFace> surface_faces(const ElementTopology& topology,
                                       std::span<const FaceRef> refs, Index surface);

/// Position of node n: row n of a (n_nodes × 3) array, m.
inline Vec3 node_point(const NodalVectors& x, Index n) {
  return Vec3(x(n, 0), x(n, 1), x(n, 2));
}

/// Shell thickness of node n (m); 0 when `thickness` is empty or has no finite value there
/// (a node of no shell).
inline Real node_thickness_of(std::span<const Real> thickness, Index n) {
  if (thickness.empty()) return 0.0;
  const Real t = thickness[n];
  return std::isfinite(t) ? t : 0.0;
}

/// Corner positions of the contact surface of `face`, m: node positions (n_nodes × 3, m),
/// moved for shell faces by t_I/2 along the unit face normal at the centre, with t_I the node
/// thickness (n_nodes, m; may be empty when there are no shells, then t = 0).
void face_corners(const ContactFace& face, const NodalVectors& position,
                  std::span<const Real> node_thickness, Vec3 corner[4]);

/// Area ½ |(x2 − x0) × (x3 − x1)| of the quad with these corners (exact when it is flat), m².
Real quad_area(const Vec3 corner[4]);

/// The nodes of a set of faces, each once, and the share of contact area each node carries.
///
/// A node's tributary area is ¼ of the area of each face around it, so that the areas of all
/// nodes sum to the area of all faces. The two sides of a shell are one piece of area: a node
/// counts each shell element once, not once per side. Areas are recomputed in parallel per
/// node through a node → face list (no races, no allocation after construction).
class SlaveNodes {
 public:
  /// Collects the nodes of `faces` and the `point_nodes` (nodes of node-based surfaces, SPEC
  /// C13) that lie on no face, ascending node index, and the node → face lists. A point node
  /// has no face: its area is fixed, `point_areas` (parallel to `point_nodes`, m², > 0), and
  /// its normal is zero. A node listed twice keeps its last area.
  SlaveNodes(std::span<const ContactFace> faces, Index node_count,
             std::span<const Index> point_nodes = {}, std::span<const Real> point_areas = {});

  /// Tributary areas and node normals on the configuration `position` (n_nodes × 3, m) of
  /// the mid-surface.
  void update_areas(std::span<const ContactFace> faces, const NodalVectors& position);
  /// update_areas for the slots with slot_needed[s] != 0 only, from the faces with
  /// face_needed[f] != 0, which must include every face around those slots (both n_slave
  /// and n_faces long; empty: all): those slots get bitwise the values update_areas gives
  /// them (the same loops, skipping), every other slot keeps what it had. The contact
  /// engine's per-increment pass, for the slave nodes that have candidate faces.
  void update_areas(std::span<const ContactFace> faces, const NodalVectors& position,
                    std::span<const char> slot_needed, std::span<const char> face_needed);

  /// Slave node indices, ascending (n_slave).
  const std::vector<Index>& nodes() const { return m_nodes; }
  /// Whether slave slot s is a point node (of a node-based surface only: no face around it).
  bool point(Index s) const { return m_face_offsets[s] == m_face_offsets[s + 1]; }
  /// Tributary area of each slave node (n_slave), m²; zero until update_areas (a point node:
  /// its fixed area from construction on).
  const std::vector<Real>& areas() const { return m_areas; }
  /// Unit normal of slave slot s: the area-weighted mean of the normals of the faces around
  /// it (outward for solids; for a shell, the normal of one side); zero until update_areas.
  Vec3 normal(Index s) const {
    return Vec3(m_normals[3 * s], m_normals[3 * s + 1], m_normals[3 * s + 2]);
  }
  /// Faces around slave slot s (one side per shell element).
  std::span<const Index> faces_of(Index s) const {
    return {m_node_faces.data() + m_face_offsets[s],
            static_cast<std::size_t>(m_face_offsets[s + 1] - m_face_offsets[s])};
  }
  /// Slot of `node` in nodes(), or NO_INDEX when it is no slave node.
  Index slot(Index node) const { return m_slot[node]; }
  Index size() const { return static_cast<Index>(m_nodes.size()); }

 private:
  std::vector<Index> m_nodes;
  std::vector<Index> m_slot;          // (n_nodes)
  std::vector<Index> m_face_offsets;  // (n_slave + 1) into m_node_faces
  std::vector<Index> m_node_faces;    // faces around each slave node, one per shell element
  std::vector<Real> m_face_area;      // (n_faces) scratch
  std::vector<Real> m_face_normal;    // (n_faces × 3) scratch: area vectors
  std::vector<Real> m_areas;
  std::vector<Real> m_normals;  // (n_slave × 3)
  /// Fixed areas of the point nodes (n_slave, m², 0 for face nodes); empty when none.
  std::vector<Real> m_point_area;
};

}  // namespace xpl::contact
