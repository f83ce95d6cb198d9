#pragma once
/// \file JOB.xdmf: an XDMF 3 temporal collection that points into JOB.h5, so that ParaView
/// and meshio can read the frames. Rewritten (atomically) when its owner asks, which
/// io/results/result_files.cpp does at most once a second during a run and at its end.

#include <filesystem>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// A node or element set as the XDMF file shows it.
struct XdmfSet {
  std::string name;          ///< deck name (XML-escaped when written)
  bool node = true;          ///< node set (else element set)
  Index size = 0;            ///< members
  std::string rows_dataset;  ///< HDF5 path of its zero-based rows (int64; for h5py users)
  std::string flag_dataset;  ///< HDF5 path of its 0/1 flag per node or element (uint8)
};

/// The mesh every frame shares, and where JOB.h5 keeps its topology (see write_mesh_group).
struct XdmfMesh {
  Index nodes = 0;  ///< rows of /mesh/coordinates
  Index cells = 0;  ///< all elements, in the row order of the cell fields (S, EVOL, ...)
  /// XDMF TopologyType: "Hexahedron" (only C3D8R), "Quadrilateral" (only S4R) or "Mixed".
  std::string topology_type = "Hexahedron";
  /// HDF5 path of the topology array: a per-type connectivity, or /mesh/mixed_topology.
  std::string topology_dataset = "/mesh/C3D8R/connectivity";
  /// Dimensions of the topology DataItem: "cells 8", "cells 4", or the length of the flat
  /// Mixed array (each cell: XDMF type code, then its node rows).
  std::string topology_dimensions = "0 8";
  /// Shell models: U, V, RF, S, STH also list UR, VR, RM, S_SNEG + S_SPOS, STH.
  bool shells = false;
  /// Models with a plastic material: frames may list PEEQ.
  bool plastic = false;
  /// Assembly models: the instance names, comma-separated in index order (empty for a flat
  /// deck); every frame then also has `node_instance`, `node_local_id`, `element_instance` and
  /// `element_local_id`, so that a picked point or cell shows the instance and its own id.
  std::string instance_names;
  /// Node and element sets, written as 0/1 attributes NSET_NAME / ELSET_NAME (not as XDMF Set
  /// elements, which ParaView's Xdmf3 reader draws as field-less blocks over the mesh).
  std::vector<XdmfSet> sets;
};

/// Writes the XDMF index of the frames in an HDF5 result file.
class XdmfWriter {
 public:
  /// `path` is the .xdmf file; `h5_name` the HDF5 file name relative to its directory.
  XdmfWriter(std::filesystem::path path, std::string h5_name);

  /// The mesh of all frames (call before the first add_frame).
  void set_mesh(XdmfMesh mesh);
  /// Adds the frame /frames/`frame` at total time `time` of step `step` (1-based, named
  /// `step_name`, at step time `step_time`) with the fields `what`; write_pending writes it.
  void add_frame(const std::string& frame, Real time, const FrameRequest& what, int step = 0,
                 const std::string& step_name = "", Real step_time = 0.0);
  /// Rewrites the file with every frame added so far, and JOB_last.xdmf: the newest frame
  /// alone, as one uniform grid that meshio.read reads; nothing when no frame came since the
  /// last write. Call it only once the frames are in JOB.h5: the file never names a frame
  /// the .h5 does not hold.
  void write_pending();
  /// Frames added since the last write_pending.
  bool pending() const { return m_pending; }
  /// Number of frames listed.
  int frame_count() const { return m_frames; }

 private:
  void write() const;
  /// The grid of one frame; `temporal`: with its Time and step Information elements (JOB.xdmf;
  /// meshio.read refuses them in the single grid of JOB_last.xdmf).
  std::string grid(const std::string& frame, Real time, const FrameRequest& what, int step,
                   const std::string& step_name, Real step_time, bool temporal) const;
  std::string data_item(const std::string& dims, const char* type,
                        const std::string& dataset) const;

  std::filesystem::path m_path;
  std::filesystem::path m_last_path;  ///< JOB_last.xdmf
  std::string m_h5_name;              ///< XML-escaped
  XdmfMesh m_mesh;
  std::string m_grids;      ///< XML of every frame so far
  std::string m_last_grid;  ///< XML of the newest frame, for JOB_last.xdmf
  int m_frames = 0;
  bool m_pending = false;  ///< frames added since the files were last written
};

}  // namespace xpl::io
