#pragma once
/// \file Corner edges of a set of master faces, for the crossed-surface check (SPEC C5): at a
/// corner of a master surface one face's two sides are not the surface's two sides (the
/// seed's caveat), so a slave edge that meets a face next to such an edge only grazes it.

#include <cstdint>
#include <span>
#include <vector>

#include "contact/contact_faces.hpp"

namespace xpl::contact {

/// Per face of `faces` (on `position`, n_nodes × 3, m; shells at their mid-surface), bit a
/// set when its perimeter edge a (corners a and a+1) is a corner of the surface: no other face
/// shares the edge with a unit normal within CROSSED_FOLD_COSINE of its own, so the edge is a
/// free rim or a fold (a block's edge). The other side of the same shell is no continuation
/// (its normal is opposite). Size faces.size().
std::vector<std::uint8_t> corner_edges(std::span<const ContactFace> faces,
                                       const NodalVectors& position);

/// Distance from point x to the segment a–b, m.
Real distance_to_segment(const Vec3& x, const Vec3& a, const Vec3& b);

}  // namespace xpl::contact
