#pragma once
/// \file JOB.xdmf: an XDMF 3 temporal collection that points into JOB.h5, so that ParaView
/// and meshio can read the frames. Rewritten (atomically) after every frame.

#include <filesystem>
#include <string>

#include "common/types.hpp"
#include "solver/output_sink.hpp"

namespace xpl::io {

/// Writes the XDMF index of the frames in an HDF5 result file.
class XdmfWriter {
 public:
  /// `path` is the .xdmf file; `h5_name` the HDF5 file name relative to its directory.
  XdmfWriter(std::filesystem::path path, std::string h5_name);

  /// Mesh sizes: nodes, hexahedra (/mesh/C3D8R/connectivity), all elements (cell fields).
  void set_mesh(Index n_nodes, Index n_hexahedra, Index n_elements);
  /// Adds the frame /frames/`frame` at total time `time` with the fields `what` and rewrites
  /// the file.
  void add_frame(const std::string& frame, Real time, const FrameRequest& what);
  /// Number of frames listed.
  int frame_count() const { return m_frames; }

 private:
  void write() const;
  std::string data_item(const std::string& dims, const char* type,
                        const std::string& dataset) const;

  std::filesystem::path m_path;
  std::string m_h5_name;  ///< XML-escaped
  Index m_nodes = 0;
  Index m_hexahedra = 0;
  Index m_elements = 0;
  std::string m_grids;  ///< XML of every frame so far
  int m_frames = 0;
};

}  // namespace xpl::io
