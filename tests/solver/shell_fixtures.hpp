#pragma once
// Shell models built in code for solver tests: a flat rectangular S4R plate.

#include <algorithm>
#include <string>
#include <vector>

#include "solver/model/model.hpp"

namespace xpl::test {

/// A plate [0,lx]×[0,ly] in the xy-plane of nx×ny S4R elements (steel by default), node
/// (i,j) at index i + (nx+1) j, normal +z. Node sets: EDGES (the whole boundary), X0 (x = 0),
/// CENTER (the node nearest the centre), TIP (x = lx), ALL. One step of `period` with energy
/// history every `history_dt` and U3 of CENTER and TIP.
struct PlateSpec {
  int nx = 20, ny = 20;
  Real lx = 1.0, ly = 1.0, thickness = 0.01;
  Real young = 200e9, poisson = 0.3, density = 7850.0;
  int integration_points = 5;
  Real period = 12e-3;
  Real history_dt = 2e-5;
  Real scale_factor = 1.0;
};

inline Index plate_node(const PlateSpec& s, int i, int j) {
  return static_cast<Index>(i + (s.nx + 1) * j);
}

inline Model make_plate(const PlateSpec& spec) {
  Model m;
  m.job_name = "plate";
  const int px = spec.nx + 1, py = spec.ny + 1;
  m.coordinates.resize(px * py, 3);
  NamedSet edges{"EDGES", {}, {}}, x0{"X0", {}, {}}, center{"CENTER", {}, {}}, tip{"TIP", {}, {}},
      all{"ALL", {}, {}};
  for (int j = 0; j < py; ++j)
    for (int i = 0; i < px; ++i) {
      const Index n = plate_node(spec, i, j);
      m.node_ids.push_back(100 + 3 * n);
      m.coordinates(n, 0) = spec.lx * i / spec.nx;
      m.coordinates(n, 1) = spec.ly * j / spec.ny;
      m.coordinates(n, 2) = 0.0;
      if (i == 0 || j == 0 || i == spec.nx || j == spec.ny) edges.members.push_back(n);
      if (i == 0) x0.members.push_back(n);
      if (i == spec.nx) tip.members.push_back(n);
      all.members.push_back(n);
    }
  center.members.push_back(plate_node(spec, spec.nx / 2, spec.ny / 2));
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i) {
      const Index c[4] = {plate_node(spec, i, j), plate_node(spec, i + 1, j),
                          plate_node(spec, i + 1, j + 1), plate_node(spec, i, j + 1)};
      m.element_ids.push_back(static_cast<ExternalId>(m.element_ids.size()) * 2 + 1);
      m.element_types.push_back(ElementType::S4R);
      m.element_nodes.insert(m.element_nodes.end(), c, c + 4);
      m.element_offsets.push_back(static_cast<Index>(m.element_nodes.size()));
      m.element_section.push_back(0);
    }
  m.source_files = {"plate.inp"};
  m.element_file.assign(m.element_ids.size(), 0);
  m.element_line.assign(m.element_ids.size(), 1);
  Material steel;
  steel.name = "STEEL";
  steel.density = spec.density;
  steel.young = spec.young;
  steel.poisson = spec.poisson;
  steel.has_density = steel.has_elastic = true;
  m.materials.push_back(steel);
  NamedSet elements{"PLATE", {}, {}};
  for (Index e = 0; e < m.element_count(); ++e) elements.members.push_back(e);
  m.element_sets.push_back(elements);
  ShellSection section;
  section.element_set = 0;
  section.material = 0;
  section.thickness = spec.thickness;
  section.integration_points = spec.integration_points;
  m.shell_sections.push_back(section);
  m.node_sets = {edges, x0, center, tip, all};
  m.initial_velocity = NodalVectors::Zero(m.node_count(), 3);

  Step step;
  step.name = "LOAD";
  step.time_period = spec.period;
  step.increment.scale_factor = spec.scale_factor;
  OutputRequest history;
  history.kind = OutputRequest::Kind::History;
  history.time_interval = spec.history_dt;
  history.energy = true;
  step.outputs.push_back(history);
  OutputRequest probe = history;
  probe.energy = false;
  probe.node_set = 2;
  probe.node_variables = {"U3"};
  step.outputs.push_back(probe);
  probe.node_set = 3;
  step.outputs.push_back(probe);
  m.steps.push_back(step);
  return m;
}

/// Fixes DOFs first..last of every node of node set `set` in step 0.
inline void fix(Model& m, Index set, int first, int last) {
  for (Index n : m.node_sets[set].members)
    m.steps[0].boundaries.push_back(
        {n, first, last, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
}

}  // namespace xpl::test
