#pragma once
// Models built in code (independent of the deck reader) and an OutputSink that keeps
// everything in memory, for solver tests.

#include <map>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "solver/model/model.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::test {

/// Keeps history rows, status lines and messages; counts frames.
class CaptureSink : public OutputSink {
 public:
  std::vector<HistorySeries> series;
  std::vector<Real> times;
  std::vector<std::vector<Real>> rows;
  std::vector<std::string> messages;
  std::vector<StatusLine> statuses;
  std::vector<Real> frame_times;
  RunStatus run_status = RunStatus::Completed;
  std::string error;

  void begin_run(const Model&) override {}
  void begin_step(const Model&, int) override {}
  void declare_history(const std::vector<HistorySeries>& s) override { series = s; }
  void write_frame(const Model&, const State& state, const FrameFields&,
                   const FrameRequest&) override {
    frame_times.push_back(state.time);
  }
  void append_history(Real time, std::span<const Real> values) override {
    times.push_back(time);
    rows.emplace_back(values.begin(), values.end());
  }
  void status(const StatusLine& line) override { statuses.push_back(line); }
  void message(Severity, const std::string& text) override { messages.push_back(text); }
  void end_run(RunStatus s, const std::string& e, const PhaseTimers&, double) override {
    run_status = s;
    error = e;
  }

  /// Column offset of a declared series.
  Index column(const std::string& path) const {
    Index offset = 0;
    for (const auto& s : series) {
      if (s.path == path) return offset;
      offset += s.width;
    }
    return NO_INDEX;
  }
  Index width(const std::string& path) const {
    for (const auto& s : series)
      if (s.path == path) return s.width;
    return 0;
  }
};

/// A box [0,lx]×[0,ly]×[0,lz] of nx×ny×nz C3D8R elements of one elastic material, with node
/// sets FIXED (x = 0) and FREE_END (x = lx), one step of `period` and history output of
/// energies and RF1/U1 every `history_dt`.
struct BoxSpec {
  int nx = 40, ny = 4, nz = 4;
  Real lx = 0.1, ly = 0.01, lz = 0.01;
  Real young = 200e9, poisson = 0.0, density = 7850.0;
  Real velocity_x = -10.0;  ///< initial velocity of every node not on FIXED
  Real period = 100e-6;
  Real history_dt = 2e-7;
  Real scale_factor = 1.0;
  bool fix_x0 = true;
  ElementType type = ElementType::C3D8R;  ///< C3D8R or C3D8
  /// `*SECTION CONTROLS, HOURGLASS=` of the box, or none (the default form).
  std::optional<HourglassType> hourglass;
};

inline Model make_box(const BoxSpec& spec) {
  Model m;
  m.job_name = "box";
  const int px = spec.nx + 1, py = spec.ny + 1, pz = spec.nz + 1;
  auto node = [&](int i, int j, int k) { return static_cast<Index>(i + px * (j + py * k)); };
  m.coordinates.resize(px * py * pz, 3);
  NamedSet fixed{"FIXED", {}, {}}, free_end{"FREE_END", {}, {}};
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j)
      for (int i = 0; i < px; ++i) {
        const Index n = node(i, j, k);
        m.node_ids.push_back(1000 + 7 * n);  // sparse ids
        m.coordinates(n, 0) = spec.lx * i / spec.nx;
        m.coordinates(n, 1) = spec.ly * j / spec.ny;
        m.coordinates(n, 2) = spec.lz * k / spec.nz;
      }
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < py; ++j) {
      fixed.members.push_back(node(0, j, k));
      free_end.members.push_back(node(spec.nx, j, k));
    }
  std::sort(fixed.members.begin(), fixed.members.end());
  std::sort(free_end.members.begin(), free_end.members.end());
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const Index c[8] = {node(i, j, k),
                            node(i + 1, j, k),
                            node(i + 1, j + 1, k),
                            node(i, j + 1, k),
                            node(i, j, k + 1),
                            node(i + 1, j, k + 1),
                            node(i + 1, j + 1, k + 1),
                            node(i, j + 1, k + 1)};
        m.element_ids.push_back(static_cast<ExternalId>(m.element_ids.size()) * 3 + 5);
        m.element_types.push_back(spec.type);
        m.element_nodes.insert(m.element_nodes.end(), c, c + 8);
        m.element_offsets.push_back(static_cast<Index>(m.element_nodes.size()));
        m.element_section.push_back(0);
      }
  Material steel;
  steel.name = "STEEL";
  steel.density = spec.density;
  steel.young = spec.young;
  steel.poisson = spec.poisson;
  steel.has_density = steel.has_elastic = true;
  m.materials.push_back(steel);
  NamedSet all{"ALL", {}, {}};
  for (Index e = 0; e < m.element_count(); ++e) all.members.push_back(e);
  m.element_sets.push_back(all);
  m.solid_sections.push_back({0, 0, NO_INDEX, {}});
  if (spec.hourglass) {
    SectionControls controls;
    controls.name = "BOX";
    controls.hourglass = *spec.hourglass;
    controls.hourglass_given = true;
    m.section_controls.push_back(controls);
    m.solid_sections[0].controls = 0;
  }
  m.node_sets = {fixed, free_end};

  m.initial_velocity = NodalVectors::Zero(m.node_count(), 3);
  for (Index n = 0; n < m.node_count(); ++n)
    if (!spec.fix_x0 || m.coordinates(n, 0) > 0.0) m.initial_velocity(n, 0) = spec.velocity_x;

  Step step;
  step.name = "IMPACT";
  step.time_period = spec.period;
  step.increment.scale_factor = spec.scale_factor;
  if (spec.fix_x0)
    for (Index n : fixed.members)
      step.boundaries.push_back({n, 1, 3, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  OutputRequest history;
  history.kind = OutputRequest::Kind::History;
  history.time_interval = spec.history_dt;
  history.energy = true;
  history.node_set = 0;
  history.node_variables = {"RF1"};
  step.outputs.push_back(history);
  OutputRequest tip = history;
  tip.energy = false;
  tip.node_set = 1;
  tip.node_variables = {"U1"};
  step.outputs.push_back(tip);
  m.steps.push_back(step);
  return m;
}

}  // namespace xpl::test
