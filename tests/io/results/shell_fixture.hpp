#pragma once
/// \file A hand-built mixed model (two S4R shells on either side of one C3D8R hex, sharing
/// nodes with it) and a state with known rotations and shell section stresses, for the
/// result-file tests of shell models.

#include <cmath>
#include <limits>
#include <vector>

#include "results/results_fixture.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::test {

/// Hex node n = i + 2 j + 4 k of the unit-index cube (0.5 × 0.25 × 0.125 m).
inline Index hex_node(int i, int j, int k) {
  return i + 2 * j + 4 * k;
}

/// Node rows of the shells: LEFT lies in z = 0 left of the hex and shares its edge x = 0,
/// RIGHT lies in z = 0.125 right of the hex and shares its top edge x = 0.5.
inline const std::vector<Index> LEFT_SHELL{8, hex_node(0, 0, 0), hex_node(0, 1, 0), 9};
inline const std::vector<Index> RIGHT_SHELL{hex_node(1, 0, 1), 10, 11, hex_node(1, 1, 1)};

/// Elements in this order: S4R 7 (left), C3D8R 11 (only if `with_hex`), S4R 42 (right);
/// 12 nodes with the sparse ids of node_id(), node set EDGE = {8, 9} (the free left edge),
/// element set SHELLS, one step LOAD of 1 ms. Without the hex, nodes 1, 3, 4, 6 are unused.
inline Model mixed_model(bool with_hex = true) {
  Model model;
  model.heading = with_hex ? "hex between two shells" : "two shells";
  model.job_name = "mixed";
  model.coordinates.resize(12, 3);
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i)
        model.coordinates.row(hex_node(i, j, k)) << 0.5 * i, 0.25 * j, 0.125 * k;
    }
  }
  model.coordinates.row(8) << -0.5, 0.0, 0.0;
  model.coordinates.row(9) << -0.5, 0.25, 0.0;
  model.coordinates.row(10) << 1.0, 0.0, 0.125;
  model.coordinates.row(11) << 1.0, 0.25, 0.125;
  for (Index n = 0; n < 12; ++n) model.node_ids.push_back(node_id(n));

  const auto add = [&](ExternalId id, ElementType type, const std::vector<Index>& nodes) {
    model.element_ids.push_back(id);
    model.element_types.push_back(type);
    model.element_nodes.insert(model.element_nodes.end(), nodes.begin(), nodes.end());
    model.element_offsets.push_back(static_cast<Index>(model.element_nodes.size()));
    model.element_section.push_back(0);
    model.add_element_source("fixture.inp", static_cast<int>(model.element_ids.size()));
  };
  add(7, ElementType::S4R, LEFT_SHELL);
  if (with_hex) {
    add(11, ElementType::C3D8R,
        {hex_node(0, 0, 0), hex_node(1, 0, 0), hex_node(1, 1, 0), hex_node(0, 1, 0),
         hex_node(0, 0, 1), hex_node(1, 0, 1), hex_node(1, 1, 1), hex_node(0, 1, 1)});
  }
  add(42, ElementType::S4R, RIGHT_SHELL);

  Material steel;
  steel.name = "STEEL";
  steel.density = 7800.0;
  steel.young = 210e9;
  steel.poisson = 0.3;
  steel.has_density = steel.has_elastic = true;
  model.materials.push_back(steel);
  model.element_sets.push_back({"SHELLS", {0, with_hex ? 2 : 1}, {}});
  model.shell_sections.push_back({0, 0, NO_INDEX, 0.01, 5, 0.0, false, {}});
  if (with_hex) {
    model.element_sets.push_back({"HEX", {1}, {}});
    model.solid_sections.push_back({1, 0, NO_INDEX, {}});
  }
  model.node_sets.push_back({"EDGE", {8, 9}, {}});
  Step step;
  step.name = "LOAD";
  step.time_period = 1e-3;
  model.steps.push_back(step);
  model.initial_velocity = NodalVectors::Zero(12, 3);
  return model;
}

/// Whether node n belongs to a shell of mixed_model().
inline bool on_shell(Index n) {
  for (const auto* shell : {&LEFT_SHELL, &RIGHT_SHELL}) {
    for (Index m : *shell) {
      if (m == n) return true;
    }
  }
  return false;
}

/// The state of frame `frame`: translations, velocities, reactions and the middle stress S as
/// tiny_state(); rotations UR_n = (0.1 n, 0.2 + n, −0.01 frame) on shell nodes (zero on the
/// others), VR = 10 UR, RM = −UR; shell element e: S_SNEG = −10 S, S_SPOS = 10 S,
/// STH = 0.01 (e + 1) (1 − 0.001 frame); hex rows of S_SNEG, S_SPOS, STH are NaN.
inline TestFrame mixed_state(const Model& model, int frame) {
  constexpr Real NaN = std::numeric_limits<Real>::quiet_NaN();
  const Index n_nodes = model.node_count();
  TestFrame state;
  state.reference = model.coordinates;
  NodalVectors u(n_nodes, 3);
  for (Index n = 0; n < n_nodes; ++n) u.row(n) << 0.01 * n, -0.02 * n, 0.001 * frame;
  state.position = state.reference + u;
  state.velocity = 10.0 * u;
  state.velocity_half = state.velocity;
  state.acceleration = 100.0 * u;
  state.reaction = -u;
  state.mass.assign(static_cast<std::size_t>(n_nodes), 1.0);
  state.rotation = NodalVectors::Zero(n_nodes, 3);
  for (Index n = 0; n < n_nodes; ++n) {
    if (on_shell(n)) state.rotation.row(n) << 0.1 * n, 0.2 + n, -0.01 * frame;
  }
  state.angular_velocity = 10.0 * state.rotation;
  state.angular_velocity_half = state.angular_velocity;
  state.reaction_moment = -state.rotation;
  state.rotary_inertia.assign(static_cast<std::size_t>(n_nodes), 1e-3);
  for (Index e = 0; e < model.element_count(); ++e) {
    const bool shell = is_shell(model.element_types[static_cast<std::size_t>(e)]);
    for (int c = 0; c < 6; ++c) {
      const Real s = (c + 1.0) * (e + 1) * (frame + 1);
      state.stress.push_back(s);
      state.stress_bottom.push_back(shell ? -10.0 * s : NaN);
      state.stress_top.push_back(shell ? 10.0 * s : NaN);
    }
    state.thickness.push_back(shell ? 0.01 * (e + 1) * (1.0 - 0.001 * frame) : NaN);
    state.volume.push_back(0.015625 * (1.0 + 0.01 * frame));
    // Hourglass state (HGSTATE), 12 values per element.
    for (int c = 0; c < 12; ++c) state.hourglass_state.push_back(0.25 * (c + 1) + e - frame);
  }
  state.time = 1e-4 * frame;
  state.step_time = state.time;
  state.increment = 10 * frame;
  state.step = 0;
  return state;
}

/// Every field, the shell thickness included.
inline FrameRequest all_fields() {
  return {.displacement = true,
          .velocity = true,
          .acceleration = true,
          .reaction = true,
          .stress = true,
          .volume = true,
          .thickness = true};
}

/// Whether two row-major value lists are equal, NaN equal to NaN.
inline bool same_values(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
  }
  return true;
}

/// Names of the links in the group at `path`, in name order.
inline std::vector<std::string> links(hid_t file, const std::string& path) {
  const io::h5::Handle group{io::h5::check_id(H5Gopen2(file, path.c_str(), H5P_DEFAULT), path),
                             H5Gclose};
  H5G_info_t info;
  io::h5::check(H5Gget_info(group.get(), &info), path);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256];
    H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name,
                       H5P_DEFAULT);
    names.emplace_back(name);
  }
  return names;
}

}  // namespace xpl::test
