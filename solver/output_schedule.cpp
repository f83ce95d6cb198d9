#include "solver/output_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace xpl {

namespace {

Real interval_of(const OutputRequest& r, Real period, int default_count) {
  if (r.time_interval > 0.0) return r.time_interval;
  const int n = r.number_interval > 0 ? r.number_interval : default_count;
  return period / n;
}

void merge(FrameRequest& into, const FrameRequest& what) {
  for (bool FrameRequest::*flag : FRAME_FLAGS) into.*flag |= what.*flag;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

/// The names of `r` that `keyword` requested.
const std::vector<std::string>& requested(const OutputRequest& r, OutputKeyword keyword) {
  if (keyword == OutputKeyword::Element) return r.element_variables;
  if (keyword == OutputKeyword::Contact) return r.contact_variables;
  return r.node_variables;
}

/// The frame flags of a field request. A request writes its flag's variables together (UR
/// also writes U); a flag that writes nothing on the model is not set (P2: STH without
/// shells).
FrameRequest frame_request(const OutputRequest& r, OutputScope scope) {
  FrameRequest what;
  for (const OutputVariable& v : OUTPUT_VARIABLES) {
    if (v.frame == nullptr || !has(requested(r, v.keyword), std::string(v.request))) continue;
    if (frame_flag_written(v.frame, scope)) what.*v.frame = true;
  }
  return what;
}

}  // namespace

void OutputSchedule::begin_step(const Model& model, int step) {
  const Step& s = model.steps[step];
  m_period = s.time_period;
  m_field.clear();
  m_history.clear();
  m_series.clear();
  m_columns.clear();
  const OutputScope scope = output_scope(model);
  for (const OutputRequest& r : s.outputs) {
    if (r.kind == OutputRequest::Kind::Field) {
      FieldRequest f;
      f.when.interval = interval_of(r, m_period, 20);
      f.when.next = f.when.interval;
      f.what = frame_request(r, scope);
      m_field.push_back(f);
      continue;
    }
    Timed t;
    t.interval = interval_of(r, m_period, 200);
    t.next = t.interval;
    m_history.push_back(t);
    if (r.energy) {
      for (const int i : energy_history_order()) {
        const EnergyVariable& energy = ENERGIES[static_cast<std::size_t>(i)];
        const std::string name(energy.name);
        if (!r.energy_variables.empty() && !has(r.energy_variables, name)) continue;
        // P2: the contact energies exist only in models with contact.
        if (energy.models == OutputModels::Contact && !model.has_contact()) continue;
        if (energy.models == OutputModels::Plastic && !scope.plastic) continue;
        m_series.push_back({"energy/" + name, 1, {}});
        m_columns.push_back({i, nullptr, 0, NO_INDEX});
      }
    }
    if (r.node_set == NO_INDEX) continue;
    const NamedSet& set = model.node_sets[r.node_set];
    for (const std::string& var : r.node_variables) {
      // "U" means U1 U2 U3; "U2" one component.
      const NodeHistoryRequest request = parse_node_history(var);
      if (request.variable == nullptr) continue;
      const OutputVariable& v = *request.variable;
      // Without shells the rotations are not allocated: their history columns hold zeros.
      const NodeValue value = written_on(v, scope) ? v.node_value : nullptr;
      for (int c = 0; c < v.width; ++c) {
        if (request.component >= 0 && request.component != c) continue;
        const std::string name(v.components[static_cast<std::size_t>(c)]);
        HistorySeries series{
            "node/" + set.name + "/" + name, static_cast<Index>(set.members.size()), {}};
        for (Index node : set.members) {
          series.node_ids.push_back(model.node_ids[node]);
          m_columns.push_back({-1, value, c, node});
        }
        m_series.push_back(std::move(series));
      }
    }
  }
}

bool OutputSchedule::fire(Timed& t, Real step_time, bool last, Real period) {
  // A relative tolerance keeps round-off in the accumulated time from skipping an output.
  const Real tol = 1e-9 * std::max(period, t.interval);
  if (!last && step_time + tol < t.next) return false;
  while (t.next <= step_time + tol) t.next += t.interval;
  return true;
}

FrameRequest OutputSchedule::field_due(Real step_time, bool last) {
  FrameRequest what;
  for (FieldRequest& f : m_field) {
    if (fire(f.when, step_time, last, m_period)) merge(what, f.what);
  }
  return what;
}

FrameRequest OutputSchedule::field_all() const {
  FrameRequest what;
  for (const FieldRequest& f : m_field) merge(what, f.what);
  return what;
}

bool OutputSchedule::history_due(Real step_time, bool last) {
  bool due = false;
  for (Timed& t : m_history) due |= fire(t, step_time, last, m_period);
  return due;
}

void OutputSchedule::history_row(const State& state, std::vector<Real>& row) const {
  row.resize(m_columns.size());
  for (std::size_t i = 0; i < m_columns.size(); ++i) {
    const Column& c = m_columns[i];
    if (c.energy >= 0)
      row[i] = ENERGIES[static_cast<std::size_t>(c.energy)].value(state.energies);
    else
      row[i] = c.value != nullptr ? c.value(state, c.node, c.component) : 0.0;
  }
}

}  // namespace xpl
