#pragma once
/// \file The mesh of a Model (model.hpp): element types and their faces, named sets,
/// surfaces and the part instances of an assembly.

#include <cstdint>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"

namespace xpl {

/// Element formulations known to the solver.
enum class ElementType : std::uint8_t {
  C3D8R,  ///< 8-node hex, one-point integration, hourglass control
  S4R,    ///< 4-node shell, one in-plane point, hourglass control (S4 is read as S4R)
  C3D8,   ///< 8-node hex, 2×2×2 points, selectively reduced (mean dilatation), no hourglass
};

/// Abaqus name of an element type ("C3D8R", "S4R"), as in decks and result files.
constexpr const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
      return "C3D8R";
    case ElementType::S4R:
      return "S4R";
    case ElementType::C3D8:
      return "C3D8";
  }
  return "UNKNOWN";
}

/// Whether elements of a type carry rotational degrees of freedom at their nodes.
constexpr bool is_shell(ElementType type) {
  return type == ElementType::S4R;
}

/// Whether elements of a type are 8-node hexahedra (C3D8R, C3D8): same nodes, faces S1..S6,
/// sections, surfaces and loads; they differ only in their element kernel.
constexpr bool is_hex(ElementType type) {
  return type == ElementType::C3D8R || type == ElementType::C3D8;
}

/// Number of nodes of an element type.
constexpr int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
    case ElementType::C3D8:
      return 8;
    case ElementType::S4R:
      return 4;
  }
  return 0;
}

/// A named set of nodes or elements (internal indices, sorted, unique).
struct NamedSet {
  std::string name;  ///< upper-case name
  std::vector<Index> members;
  SourceLocation where;
};

/// Corner nodes (0-based, element node order) of the C3D8R faces S1..S6. The right-hand
/// normal of each corner cycle points into the element (Abaqus' face numbering).
inline constexpr int HEX_FACE_NODES[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                             {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};

/// Faces of an S4R element: SNEG (the side opposite the normal n = (x3−x1)×(x4−x2)) and SPOS.
inline constexpr std::uint8_t SHELL_FACE_NEG = 0;
inline constexpr std::uint8_t SHELL_FACE_POS = 1;

/// One face of an element: C3D8R faces S1..S6 are stored as 0..5 (Abaqus numbering:
/// S1 = nodes 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4, S6 = 4-8-5-1);
/// S4R faces are SHELL_FACE_NEG (SNEG) and SHELL_FACE_POS (SPOS).
struct ElementFace {
  Index element = NO_INDEX;
  std::uint8_t face = 0;
};

/// `*SURFACE, TYPE=ELEMENT|NODE, NAME=`.
struct Surface {
  enum class Type { Element, Node };
  std::string name;  ///< upper-case name
  Type type = Type::Element;
  std::vector<ElementFace> faces;  ///< TYPE=ELEMENT
  std::vector<Index> nodes;        ///< TYPE=NODE, ascending, each once
  /// TYPE=NODE: the area (or weight) the data line gives each node (parallel to `nodes`), m²;
  /// NaN where the line gives none (the contact domain then takes its default, SPEC C13).
  std::vector<Real> node_areas;
  SourceLocation where;
};

/// A part instance of an assembly (`*INSTANCE, NAME=, PART=`): its nodes and elements carry
/// the ids of the part, which repeat from instance to instance; the model numbers them
/// `offset + local id` (Model::node_ids, element_ids) and keeps the local ids beside.
struct PartInstance {
  std::string name;                                ///< upper-case instance name
  std::string part;                                ///< upper-case part name
  ExternalId node_offset = 0, element_offset = 0;  ///< model id = offset + local id
  Index nodes = 0, elements = 0;                   ///< how many the instance has
  SourceLocation where;                            ///< the *INSTANCE line
};

}  // namespace xpl
