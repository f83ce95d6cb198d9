#include "io/results/xdmf_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "solver/output_variables.hpp"

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

/// XDMF AttributeType of a variable with `width` components.
const char* attribute_type(int width) {
  if (width == 6) return "Tensor6";
  return width == 3 ? "Vector" : "Scalar";
}

}  // namespace

XdmfWriter::XdmfWriter(std::filesystem::path path, std::string h5_name)
    : m_path(std::move(path)), m_h5_name(xml_escape(h5_name)) {}

void XdmfWriter::set_mesh(XdmfMesh mesh) {
  m_mesh = std::move(mesh);
}

std::string XdmfWriter::data_item(const std::string& dims, const char* type,
                                  const std::string& dataset) const {
  return std::string("<DataItem Dimensions=\"") + dims + "\" DataType=\"" + type +
         "\" Precision=\"8\" Format=\"HDF\">" + m_h5_name + ":" + dataset + "</DataItem>";
}

void XdmfWriter::add_frame(const std::string& frame, Real time, const FrameRequest& what) {
  const std::string nodes = std::to_string(m_mesh.nodes);
  const std::string cells = std::to_string(m_mesh.cells);
  const std::string prefix = "/frames/" + frame + "/";
  std::string grid = "      <Grid Name=\"frame_" + frame + "\" GridType=\"Uniform\">\n";
  grid += "        <Time Value=\"" + exact(time) + "\"/>\n";
  grid += "        <Topology TopologyType=\"" + m_mesh.topology_type + "\" NumberOfElements=\"" +
          cells + "\">\n          " +
          data_item(m_mesh.topology_dimensions, "Int", m_mesh.topology_dataset) +
          "\n        </Topology>\n";
  grid += "        <Geometry GeometryType=\"XYZ\">\n          " +
          data_item(nodes + " 3", "Float", "/mesh/coordinates") + "\n        </Geometry>\n";
  for (const OutputVariable* v : frame_variables(what, {m_mesh.shells, m_mesh.plastic})) {
    const std::string name(v->name);
    const bool node = v->location == OutputLocation::Node;
    std::string dims = node ? nodes : cells;
    if (v->width > 1) dims.append(" ").append(std::to_string(v->width));
    grid += "        <Attribute Name=\"" + name + "\" AttributeType=\"" + attribute_type(v->width) +
            "\" Center=\"" + (node ? "Node" : "Cell") + "\">\n          " +
            data_item(dims, "Float", prefix + name) + "\n        </Attribute>\n";
  }
  grid += "      </Grid>\n";
  m_grids += grid;
  ++m_frames;
  write();
}

void XdmfWriter::write() const {
  // Write a sibling file and rename it over the old one: readers never see a partial file.
  std::filesystem::path temporary = m_path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
        << "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"frames\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"
        << m_grids << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);  // no stray .tmp on a full disk
      throw std::runtime_error("cannot write " + temporary.string());
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, m_path, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot rename " + temporary.string() + " to " + m_path.string() +
                             ": " + error.message());
  }
}

}  // namespace xpl::io
