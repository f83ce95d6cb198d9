#pragma once
/// \file Lower bounds of the distance from a node to a face, for the search's reach test
/// (contact_search.cpp, admissible()): what a face's corners give before any closest point.
///
/// The parts that depend on the face alone (its box and its extent along its unit normal) are
/// worked out once per face and search (CornerBounds), the rest per node; the bounds are the
/// same numbers, bit for bit, as when all of it is worked out per node and face.

#include "contact/contact_faces.hpp"

namespace xpl::contact {

/// The box of a face's four corners, and their extent along the face's unit normal.
struct CornerBounds {
  Real lo[3]{}, hi[3]{};  ///< the corners' box, m
  Real extent = 0.0;      ///< its largest side, m
  Real along_lo = 0.0;    ///< lowest corner·unit, m
  Real along_hi = 0.0;    ///< highest corner·unit, m
  Real scale = 0.0;       ///< largest |coordinate| of a corner, m
};

/// The bounds of the corners `corner` (m) along the unit normal `unit`.
void bound_corners(const Vec3 corner[4], const Vec3& unit, CornerBounds& out);

/// A lower bound (m) of the distance from `p` (m) to the bilinear face whose corners have the
/// bounds `b` along `unit` (contact_search.cpp).
Real distance_below(const CornerBounds& b, const Vec3& p, const Vec3& unit);

/// Whether `p` (m) lies certainly behind every corner of the mid-surface with bounds `mid`
/// along `unit`, beyond the rounding of admissible()'s round-edge test.
bool behind_mid_surface(const CornerBounds& mid, const Vec3& p, const Vec3& unit);

/// Whether the face with corner bounds `corner` along its unit normal `unit` certainly matters
/// to no search of the node at `p` (contact_search.cpp, admissible()); `mid`: a round face's
/// mid-surface bounds (else null).
bool out_of_reach(const CornerBounds& corner, const Vec3& unit, const Vec3& p, Real limit,
                  Real half_t, Real margin, Real nearer_than, const CornerBounds* mid, bool behind,
                  Real round);

}  // namespace xpl::contact
