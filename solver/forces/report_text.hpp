#pragma once
/// \file What the reports of the initial passes share (overclosure_report.cpp,
/// clearance_report.cpp): how they write numbers, faces and nodes into .msg lines and the
/// columns of their result tables. Private to solver/forces/.

#include <cstdint>
#include <cstdio>
#include <string>

#include "solver/forces/overclosure_report.hpp"

namespace xpl::report {

/// Face codes of the tables: hex S1..S6 = 1..6, shell SPOS = 7, SNEG = 8.
inline constexpr const char* FACE_CODES = "1..6: S1..S6 of a C3D8R; 7: SPOS, 8: SNEG of an S4R";

inline std::string real_text(Real v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4e", v);
  return buffer;
}

inline std::string vector_text(const contact::Vec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.4f, %.4f, %.4f)", v[0], v[1], v[2]);
  return buffer;
}

inline std::int64_t face_code(const contact::ContactFace& face) {
  if (!face.shell) return face.face + 1;
  return face.face == contact::SHELL_SPOS ? 7 : 8;
}

/// A table column of deck ids or codes.
inline TableColumn ids(const std::string& name, const std::string& description) {
  TableColumn c;
  c.name = name;
  c.integer = true;
  c.description = description;
  return c;
}

/// A table column of `width` reals per row.
inline TableColumn reals(const std::string& name, const std::string& description, Index width = 1) {
  TableColumn c;
  c.name = name;
  c.width = width;
  c.description = description;
  return c;
}

/// "face S3 of element 12", "node 7": how the messages name a contact face and a node.
class Names {
 public:
  Names(const contact::ContactDomain& domain, const Model& model)
      : m_domain(domain), m_model(model) {}
  std::string face(Index f) const {
    const contact::ContactFace& cf = m_domain.faces()[f];
    return "face " +
           face_label(cf.shell ? contact::ElementKind::Shell : contact::ElementKind::Hex, cf.face) +
           " of element " + std::to_string(m_model.element_ids[cf.element]);
  }
  std::string node(Index node) const { return "node " + std::to_string(m_model.node_ids[node]); }
  /// A surface of the contact domain by name, "?" for none.
  std::string surface(Index surface) const {
    return surface == NO_INDEX ? std::string("?") : m_domain.surface_name(surface);
  }

 private:
  const contact::ContactDomain& m_domain;
  const Model& m_model;
};

}  // namespace xpl::report
