#pragma once
/// \file The /mesh group of JOB.h5: node and element ids, reference coordinates, the
/// connectivity of each element type, the XDMF topology of mixed meshes, and the sets.
///
/// Element rows: every cell field of a frame (S, EVOL, STH, ...) has one row per element in
/// the order of /mesh/element_ids, whatever the element type. /mesh/TYPE holds the elements
/// of one type in that same order. A mesh with more than one element type also stores
/// /mesh/TYPE/element_rows (rows into /mesh/element_ids) and /mesh/mixed_topology, the XDMF
/// "Mixed" array in element order (per element: XDMF cell code, then its zero-based node rows),
/// so that the cells in the XDMF file line up with the cell fields.

#include <cstdint>
#include <vector>

#include "io/result_tools/h5_handles.hpp"
#include "io/results/xdmf_writer.hpp"
#include "solver/model/model.hpp"

namespace xpl::io {

/// XDMF name of the cell shape of an element type ("Hexahedron", "Quadrilateral").
const char* xdmf_cell_name(ElementType type);

/// XDMF code of the cell shape of an element type in a Mixed topology (Hexahedron 9,
/// Quadrilateral 5).
std::int64_t xdmf_cell_code(ElementType type);

/// A nodal field (n_nodes × 3, column-major in memory) as the row-major buffer HDF5 stores.
std::vector<double> row_major(const NodalVectors& field);

/// Writes the group /mesh below `file` and returns how the XDMF file finds its topology.
XdmfMesh write_mesh_group(hid_t file, const Model& model);

}  // namespace xpl::io
