#include "io/results/xdmf_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "solver/output/output_variables.hpp"

namespace xpl::io {

namespace {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Shortest text that reads back as the same double.
std::string exact(Real value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

/// XDMF AttributeType of a variable with `width` components. ParaView's Xdmf3 reader makes
/// the first "Scalar" of a grid its active scalars, which ParaView colours by when the data
/// is shown, and the first "Vector" the active vectors, which Warp By Vector offers first:
/// so the one scalar `colour` (colour_field) is "Scalar", every other one "None" (an array
/// like any other), and U, the first vector of a frame, is the one Warp By Vector takes.
const char* attribute_type(int width, bool colour) {
  if (width == 6) return "Tensor6";
  if (width == 3) return "Vector";
  return colour ? "Scalar" : "None";
}

/// The field a frame's model is coloured by when ParaView shows it: the largest Mises stress
/// through the thickness on shell models, else the Mises stress, else the first scalar of the
/// frame (PEEQ, EVOL, contact pressure, ...); "" for a frame without one.
std::string_view colour_field(const std::vector<const OutputVariable*>& variables) {
  for (const std::string_view preferred : {"MISES_MAX", "MISES"})
    for (const OutputVariable* v : variables)
      if (v->name == preferred) return v->name;
  for (const OutputVariable* v : variables)
    if (v->width == 1) return v->name;
  return "";
}

/// Writes `text` to a sibling file and renames it over `path`: readers never see a partial
/// file.
void write_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);  // no stray .tmp on a full disk
      throw std::runtime_error("cannot write " + temporary.string());
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot rename " + temporary.string() + " to " + path.string() + ": " +
                             error.message());
  }
}

}  // namespace

XdmfWriter::XdmfWriter(std::filesystem::path path, std::string h5_name)
    : m_path(std::move(path)), m_h5_name(xml_escape(h5_name)) {
  m_last_path = m_path;
  m_last_path.replace_filename(m_path.stem().string() + "_last.xdmf");
}

void XdmfWriter::set_mesh(XdmfMesh mesh) {
  m_mesh = std::move(mesh);
}

std::string XdmfWriter::data_item(const std::string& dims, const char* type,
                                  const std::string& dataset) const {
  const char* precision = std::string_view(type) == "UInt" ? "1" : "8";
  return std::string("<DataItem Dimensions=\"") + dims + "\" DataType=\"" + type +
         "\" Precision=\"" + precision + "\" Format=\"HDF\">" + m_h5_name + ":" + dataset +
         "</DataItem>";
}

std::string XdmfWriter::grid(const std::string& frame, Real time, const FrameRequest& what,
                             int step, const std::string& step_name, Real step_time,
                             bool temporal) const {
  const std::string nodes = std::to_string(m_mesh.nodes);
  const std::string cells = std::to_string(m_mesh.cells);
  const std::string prefix = "/frames/" + frame + "/";
  const auto attribute = [&](const std::string& name, const char* type, bool node,
                             const std::string& dims, const char* data_type,
                             const std::string& dataset) {
    return "        <Attribute Name=\"" + xml_escape(name) + "\" AttributeType=\"" + type +
           "\" Center=\"" + (node ? "Node" : "Cell") + "\">\n          " +
           data_item(dims, data_type, dataset) + "\n        </Attribute>\n";
  };
  std::string grid = "      <Grid Name=\"frame_" + frame + "\" GridType=\"Uniform\">\n";
  // meshio.read rejects Time and Information elements (other than its own) in a single
  // grid: the last-frame file carries neither (its frame's time is in JOB.xdmf and JOB.h5).
  if (temporal) {
    grid += "        <Time Value=\"" + exact(time) + "\"/>\n";
    grid += "        <Information Name=\"step\" Value=\"" + std::to_string(step) + "\"/>\n";
    grid += "        <Information Name=\"step_name\" Value=\"" + xml_escape(step_name) + "\"/>\n";
    grid += "        <Information Name=\"step_time\" Value=\"" + exact(step_time) + "\"/>\n";
    if (!m_mesh.instance_names.empty())
      grid += "        <Information Name=\"instances\" Value=\"" +
              xml_escape(m_mesh.instance_names) + "\"/>\n";
  }
  grid += "        <Topology TopologyType=\"" + m_mesh.topology_type + "\" NumberOfElements=\"" +
          cells + "\">\n          " +
          data_item(m_mesh.topology_dimensions, "Int", m_mesh.topology_dataset) +
          "\n        </Topology>\n";
  grid += "        <Geometry GeometryType=\"XYZ\">\n          " +
          data_item(nodes + " 3", "Float", "/mesh/coordinates") + "\n        </Geometry>\n";
  // Deck ids, so that a picked point or cell shows its node or element number (as global
  // ids: not the scalars ParaView colours by).
  grid += attribute("node_id", "GlobalId", true, nodes, "Int", "/mesh/node_ids");
  grid += attribute("element_id", "GlobalId", false, cells, "Int", "/mesh/element_ids");
  if (!m_mesh.instance_names.empty()) {
    // Assembly models: the instance (index into the names of Information "instances", -1 at
    // the assembly level) and the id within it, as the deck wrote it (arrays, not scalars
    // ParaView would colour by).
    grid += attribute("node_instance", "None", true, nodes, "Int", "/mesh/node_instance");
    grid += attribute("node_local_id", "None", true, nodes, "Int", "/mesh/node_local_ids");
    grid += attribute("element_instance", "None", false, cells, "Int", "/mesh/element_instance");
    grid += attribute("element_local_id", "None", false, cells, "Int", "/mesh/element_local_ids");
  }
  const std::vector<const OutputVariable*> variables =
      frame_variables(what, {m_mesh.shells, m_mesh.plastic});
  const std::string_view colour = colour_field(variables);
  for (const OutputVariable* v : variables) {
    const std::string name(v->name);
    const bool node = v->location == OutputLocation::Node;
    std::string dims = node ? nodes : cells;
    if (v->width > 1) dims.append(" ").append(std::to_string(v->width));
    if (v->width == 6) {
      // Tensors: the copies in VTK's Tensor6 order (XX YY ZZ XY YZ XZ) and global axes, so
      // that ParaView and meshio label S13 as XZ; shell models add the local-axes copies.
      grid += attribute(name, "Tensor6", node, dims, "Float", "/xdmf/" + frame + "/" + name);
      if (m_mesh.shells) {
        grid += attribute(name + "_LOCAL", "Tensor6", node, dims, "Float",
                          "/xdmf/" + frame + "/" + name + "_LOCAL");
      }
      continue;
    }
    grid += attribute(name, attribute_type(v->width, v->name == colour), node, dims, "Float",
                      prefix + name);
  }
  // Sets as 0/1 attributes (NSET_NAME on the nodes, ELSET_NAME on the cells), not as XDMF
  // Set elements: ParaView's Xdmf3 reader turns every Set on and draws each as a block without
  // fields over the mesh (a grey model under a correct colour bar), and meshio reads no Set.
  // A set is then an array to colour by or to threshold.
  for (const XdmfSet& set : m_mesh.sets) {
    const std::string kind = set.node ? "NSET_" : "ELSET_";
    grid += attribute(kind + set.name, "None", set.node, set.node ? nodes : cells, "UInt",
                      set.flag_dataset);
  }
  grid += "      </Grid>\n";
  return grid;
}

void XdmfWriter::add_frame(const std::string& frame, Real time, const FrameRequest& what, int step,
                           const std::string& step_name, Real step_time) {
  m_grids += grid(frame, time, what, step, step_name, step_time, true);
  m_last_grid = grid(frame, time, what, step, step_name, step_time, false);
  ++m_frames;
  m_pending = true;
}

void XdmfWriter::write_pending() {
  if (!m_pending) return;
  write();
  // The newest frame alone: meshio.read and the meshio CLI read a single uniform grid.
  write_file(m_last_path,
             "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
             "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
             "  <Domain>\n" +
                 m_last_grid +
                 "  </Domain>\n"
                 "</Xdmf>\n");
  m_pending = false;
}

void XdmfWriter::write() const {
  write_file(m_path,
             "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
             "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
             "  <Domain>\n"
             "    <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n" +
                 m_grids +
                 "    </Grid>\n"
                 "  </Domain>\n"
                 "</Xdmf>\n");
}

}  // namespace xpl::io
