#include "io/results/xdmf_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

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
  const auto attribute = [&](const char* name, const char* type, const char* center,
                             const std::string& dims) {
    grid += std::string("        <Attribute Name=\"") + name + "\" AttributeType=\"" + type +
            "\" Center=\"" + center + "\">\n          " + data_item(dims, "Float", prefix + name) +
            "\n        </Attribute>\n";
  };
  const auto vector = [&](const char* name) { attribute(name, "Vector", "Node", nodes + " 3"); };
  const bool shells = m_mesh.shells;
  if (what.displacement) vector("U");
  if (what.displacement && shells) vector("UR");
  if (what.velocity) vector("V");
  if (what.velocity && shells) vector("VR");
  if (what.acceleration) vector("A");
  if (what.reaction) vector("RF");
  if (what.reaction && shells) vector("RM");
  if (what.stress) {
    attribute("S", "Tensor6", "Cell", cells + " 6");
    attribute("MISES", "Scalar", "Cell", cells);
  }
  if (what.stress && shells) {
    attribute("S_SNEG", "Tensor6", "Cell", cells + " 6");
    attribute("S_SPOS", "Tensor6", "Cell", cells + " 6");
  }
  if (what.volume) attribute("EVOL", "Scalar", "Cell", cells);
  if (what.thickness && shells) attribute("STH", "Scalar", "Cell", cells);
  if (what.contact_stress) {
    attribute("CPRESS", "Scalar", "Node", nodes);
    vector("CSHEAR");
  }
  if (what.contact_status) attribute("CSTATUS", "Scalar", "Node", nodes);
  if (what.contact_force) {
    vector("CNORMF");
    vector("CSHEARF");
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
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
  }
  std::error_code error;
  std::filesystem::rename(temporary, m_path, error);
  if (error) {
    throw std::runtime_error("cannot rename " + temporary.string() + " to " + m_path.string() +
                             ": " + error.message());
  }
}

}  // namespace xpl::io
