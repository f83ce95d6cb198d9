#pragma once
/// \file The contact domain of a step: which slave nodes may touch which master faces, with
/// what weight and surface interaction (stage 1 of the contact pipeline, set up once per
/// step).
///
/// The caller (the solver) describes the domain in deck terms: contact surfaces (all exterior
/// faces, or the faces of a `*SURFACE`), included pairs (balanced, or one-sided slave →
/// master), excluded pairs and interaction assignments. Here that becomes one list of faces,
/// each tagged with the set of contact surfaces it belongs to (a bit mask), the slave nodes
/// (every node of a face, and the nodes of node-based surfaces) tagged the same way, and a rule
/// that answers, for a slave node and a face, "may they touch, and with which weight".
///
/// Weights: in a balanced pair both surfaces act as slave against the other, so every touch
/// is seen twice (node of A on a face of B and node of B on a face of A) and each view
/// carries half the force (weight ½, as Abaqus' balanced master–slave weighting). A one-sided
/// pair (`*CONTACT PAIR`) has one view with weight 1. Between a rigid body and a deformable
/// body both views act, each with weight 1: the deformable nodes on the rigid faces, and the
/// rigid body's nodes on the deformable faces, so that a rigid body meshed finer than its
/// partner (a rigid punch, a rod, a projectile) cannot pass with its corners between the
/// partner's nodes. Where the meshes match both views hold a touch and the contact is twice
/// as stiff, within the node budget of the engine. Two rigid bodies never touch.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "contact/contact_faces.hpp"

namespace xpl::contact {

/// At most this many contact surfaces take part in one domain (one bit each).
inline constexpr int MAX_CONTACT_SURFACES = 64;

/// One surface of the domain description.
struct DomainSurface {
  std::string name;            ///< for messages and history names
  bool all_exterior = false;   ///< every exterior solid face and both sides of every shell
  std::vector<FaceRef> faces;  ///< the faces of an element-based `*SURFACE`
  /// The nodes of a node-based `*SURFACE, TYPE=NODE` (SPEC C13): slave nodes only, no faces.
  /// A pair naming it must be one-sided with it first (the caller sees to that).
  std::vector<Index> nodes{};
  /// Contact area of each of `nodes` (parallel, m²); NaN or empty: POINT_NODE_DEFAULT_AREA.
  std::vector<Real> node_areas{};
};

/// A pair of surfaces (indices into DomainSpec::surfaces).
struct DomainPair {
  Index first = 0;
  Index second = 0;
  /// false: balanced (both views); true: `first` is the slave, `second` the master.
  bool one_sided = false;
};

/// What the caller knows about the domain of a step.
struct DomainSpec {
  std::vector<DomainSurface> surfaces;
  std::vector<DomainPair> inclusions;  ///< pairs that may touch (self contact: first == second)
  std::vector<DomainPair> exclusions;  ///< pairs that may not, whatever the inclusions say
  /// Interaction of a pair (into the caller's interaction list); the first match wins, in
  /// either order, `default_interaction` otherwise.
  std::vector<std::pair<DomainPair, Index>> interactions;
  Index default_interaction = NO_INDEX;
  /// Rigid body of each element (n_elements), NO_INDEX for deformable ones; empty: none.
  std::vector<Index> element_body;
  /// Whether each node belongs to a rigid body (n_nodes); empty: none. Read for point nodes
  /// only (a face node is rigid when one of its faces is).
  std::vector<char> rigid_node;
};

/// The faces, slave nodes and pairing rule of one step.
class ContactDomain {
 public:
  /// Builds the domain on the reference geometry `position` (n_nodes × 3, m; used for the
  /// depth of each face). Throws std::invalid_argument for more than MAX_CONTACT_SURFACES
  /// surfaces or a surface/pair index out of range.
  ContactDomain(const DomainSpec& spec, const ElementTopology& topology,
                const NodalVectors& position);

  const std::vector<ContactFace>& faces() const { return m_faces; }
  const SlaveNodes& slaves() const { return m_slaves; }
  SlaveNodes& slaves() { return m_slaves; }
  /// Whether slave slot s belongs to a rigid body (it touches deformable faces only).
  bool slave_rigid(Index s) const { return m_slave_rigid[s] != 0; }
  /// Whether every face around slave slot s is a shell side (a double-sided node); false for
  /// a point node.
  bool slave_double_sided(Index s) const { return m_slave_shell[s] != 0; }
  /// Whether slave slot s is a point node: a node of a node-based surface on no face of the
  /// domain. It has no normal of its own, so it may touch a face of either orientation (as a
  /// free shell edge may), and it has no facet edges (no crossed-surface check, SPEC C5).
  bool slave_point(Index s) const { return m_slaves.point(s); }
  /// Number of point nodes (slave_point).
  Index point_count() const { return m_point_count; }
  /// Whether slave slot s lies on a free edge of a shell (an edge of one shell element only):
  /// such a node can touch a face edge-on (a tube end on a plate).
  bool slave_on_free_edge(Index s) const { return m_slave_free_edge[s] != 0; }
  bool face_rigid(Index f) const { return m_face_rigid[f] != 0; }
  /// How deep (m) a node may be below face f and still be taken as touching it: half the
  /// element's depth behind a solid face, half the thickness of a shell (the mid-surface).
  Real face_depth(Index f) const { return m_face_depth[f]; }
  /// The hex face of the domain across hex face f's edge `edge` (from corner `edge` to corner
  /// `edge` + 1): the one other hex face with both of the edge's nodes, the surface's next face
  /// there; NO_INDEX when there is none or more than one, or f is a shell face.
  Index face_across(Index f, int edge) const { return m_face_across[f][edge]; }
  std::span<const Real> face_depths() const { return m_face_depth; }

  /// Weight of the touch of slave slot s on face f: 0 when they may not touch, ½ for a view
  /// of a balanced pair, 1 for a one-sided one. The included pair that matches first is
  /// returned in `pair` (for per-pair output).
  Real weight(Index s, Index f, Index& pair) const;
  /// Interaction of slave slot s touching face f (DomainSpec::interactions rule).
  Index interaction(Index s, Index f) const;
  /// Whether slave slot s may touch some face through interaction `interaction`: the default
  /// interaction, or an assignment of it names a surface of the node (a bound, for checks).
  bool may_use(Index s, Index interaction) const;

  /// Name of domain surface k (DomainSpec::surfaces).
  const std::string& surface_name(Index k) const { return m_surface_names[k]; }
  Index surface_count() const { return static_cast<Index>(m_surface_names.size()); }
  /// The surface slave slot s acts for when it touches face f through included pair `pair`
  /// (the pair's slave side in that view).
  Index slave_surface(Index s, Index f, Index pair) const;
  /// The surface of face f named first in `pair` (its master side in that view).
  Index master_surface(Index s, Index f, Index pair) const;

  /// Number of included pairs (history output per pair).
  Index pair_count() const { return static_cast<Index>(m_inclusions.size()); }
  /// Whether the domain is empty (no face, or no slave node that may touch anything).
  bool empty() const { return m_faces.empty(); }

 private:
  std::vector<std::uint64_t> m_face_mask;  // filled while m_faces is built: declared first
  std::vector<ContactFace> m_faces;
  std::vector<char> m_face_rigid;
  std::vector<Real> m_face_depth;
  std::vector<std::array<Index, 4>> m_face_across;
  SlaveNodes m_slaves;
  std::vector<std::uint64_t> m_slave_mask;
  std::vector<char> m_slave_rigid;
  std::vector<char> m_slave_shell;
  std::vector<char> m_slave_free_edge;
  std::vector<std::string> m_surface_names;
  std::vector<DomainPair> m_inclusions;
  std::vector<DomainPair> m_exclusions;
  std::vector<std::pair<DomainPair, Index>> m_interactions;
  Index m_default_interaction = NO_INDEX;
  bool m_everything = false;  ///< one balanced ALL EXTERIOR self pair, nothing excluded
  Index m_point_count = 0;
};

}  // namespace xpl::contact
