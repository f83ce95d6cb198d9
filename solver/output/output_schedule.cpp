#include "solver/output/output_schedule.hpp"

#include <algorithm>
#include <cmath>

#include "solver/message_text.hpp"

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

std::string located(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line);
}

/// The name a deck uses for the variables of frame flag `flag` ("U", "S", "CSTRESS").
std::string flag_name(bool FrameRequest::*flag) {
  for (const OutputVariable& v : OUTPUT_VARIABLES)
    if (v.frame == flag) return std::string(v.request);
  return "?";
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

bool uses_default_output(const Model& model) {
  return std::all_of(model.steps.begin(), model.steps.end(),
                     [](const Step& s) { return s.outputs.empty(); });
}

std::vector<OutputRequest> default_output_requests() {
  OutputRequest field;
  field.kind = OutputRequest::Kind::Field;
  field.number_interval = 1;  // the end of the step
  field.node_variables = {"U", "V"};
  field.element_variables = {"S", "PEEQ"};  // PEEQ is left out of elastic models
  OutputRequest history;
  history.kind = OutputRequest::Kind::History;
  history.number_interval = 200;
  history.energy = true;  // every energy of the model
  return {field, history};
}

std::string default_output_warning() {
  return "the deck has no output requests (*OUTPUT, *NODE OUTPUT, ...); xpl writes its "
         "default output: the last frame of each step (U, V, S, and PEEQ of plastic models) "
         "besides frame 0, and the whole-model energies 200 times a step. Add *OUTPUT, FIELD "
         "and *OUTPUT, HISTORY requests to choose what is written";
}

void OutputSchedule::begin_step(const Model& model, int step) {
  const Step& s = model.steps[step];
  m_period = s.time_period;
  m_field.clear();
  m_history.clear();
  m_series.clear();
  m_columns.clear();
  m_series_owner.clear();
  m_history_repeats.clear();
  const OutputScope scope = output_scope(model);
  const bool defaults = uses_default_output(model);
  if (defaults && step == 0) m_warnings.push_back(default_output_warning());
  const std::vector<OutputRequest> default_requests =
      defaults ? default_output_requests() : std::vector<OutputRequest>{};
  for (const OutputRequest& r : defaults ? default_requests : s.outputs) {
    if (r.kind == OutputRequest::Kind::Field) {
      FieldRequest f;
      f.when.interval = interval_of(r, m_period, 20);
      f.when.next = f.when.interval;
      f.when.where = r.where;
      f.what = frame_request(r, scope);
      m_field.push_back(f);
      continue;
    }
    Timed t;
    t.interval = interval_of(r, m_period, 200);
    t.next = t.interval;
    t.where = r.where;
    m_history.push_back(t);
    const std::size_t index = m_history.size() - 1;
    if (r.energy) {
      for (const int i : energy_history_order()) {
        const EnergyVariable& energy = ENERGIES[static_cast<std::size_t>(i)];
        const std::string name(energy.name);
        if (!r.energy_variables.empty() && !has(r.energy_variables, name)) continue;
        // P2: the contact energies exist only in models with contact.
        if (energy.models == OutputModels::Contact && !model.has_contact()) continue;
        if (energy.models == OutputModels::Plastic && !scope.plastic) continue;
        if (!first_series("energy/" + name, index)) continue;
        m_series.push_back({"energy/" + name, 1, {}, name, std::string(energy.unit)});
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
        const std::string path = "node/" + set.name + "/" + name;
        if (!first_series(path, index)) continue;
        HistorySeries series{
            path, static_cast<Index>(set.members.size()), {}, name, std::string(v.unit)};
        for (Index node : set.members) {
          series.node_ids.push_back(model.node_ids[node]);
          m_columns.push_back({-1, value, c, node});
        }
        m_series.push_back(std::move(series));
      }
    }
  }
  for (const Repeat& repeat : m_history_repeats)
    m_notes.push_back("step " + std::to_string(step + 1) + ": *OUTPUT, HISTORY at " +
                      located(m_history[repeat.request].where) + " asks again for " +
                      joined(repeat.names) + " (already requested at " +
                      located(m_history[repeat.owner].where) +
                      "): each is written once, in every history row (rows fall due at the "
                      "times of every request, so at the finer interval)");
  merge_field_requests(step);
  m_history_nodes.clear();
  for (const Column& c : m_columns)
    if (c.energy < 0) m_history_nodes.push_back(c.node);
  std::sort(m_history_nodes.begin(), m_history_nodes.end());
  m_history_nodes.erase(std::unique(m_history_nodes.begin(), m_history_nodes.end()),
                        m_history_nodes.end());
}

bool OutputSchedule::first_series(const std::string& path, std::size_t request) {
  const auto owner = std::find_if(m_series_owner.begin(), m_series_owner.end(),
                                  [&](const auto& entry) { return entry.first == path; });
  if (owner == m_series_owner.end()) {
    m_series_owner.emplace_back(path, request);
    return true;
  }
  const std::size_t first = owner->second;
  // Requests split by a second *NODE OUTPUT share their keyword: one note per keyword pair.
  const auto same = [&](std::size_t a, std::size_t b) {
    return located(m_history[a].where) == located(m_history[b].where);
  };
  auto repeat = std::find_if(
      m_history_repeats.begin(), m_history_repeats.end(),
      [&](const Repeat& r) { return same(r.request, request) && same(r.owner, first); });
  if (repeat == m_history_repeats.end()) {
    m_history_repeats.push_back({request, first, {}});
    repeat = m_history_repeats.end() - 1;
  }
  // "energy/ALLKE" -> ALLKE, "node/FIXED/RF1" -> FIXED/RF1: the names of the deck.
  const std::size_t slash = path.find('/');
  repeat->names.push_back(path.substr(slash + 1));
  return false;
}

void OutputSchedule::merge_field_requests(int step) {
  // Per pair (request losing a flag, request keeping it): the flags moved.
  std::vector<Repeat> repeats;
  for (bool FrameRequest::*flag : FRAME_FLAGS) {
    std::size_t owner = m_field.size();
    for (std::size_t i = 0; i < m_field.size(); ++i)
      if (m_field[i].what.*flag &&
          (owner == m_field.size() || m_field[i].when.interval < m_field[owner].when.interval))
        owner = i;
    for (std::size_t i = 0; i < m_field.size(); ++i) {
      if (i == owner || !(m_field[i].what.*flag)) continue;
      m_field[i].what.*flag = false;
      auto repeat = std::find_if(repeats.begin(), repeats.end(), [&](const Repeat& r) {
        return r.request == i && r.owner == owner;
      });
      if (repeat == repeats.end()) {
        repeats.push_back({i, owner, {}});
        repeat = repeats.end() - 1;
      }
      repeat->names.push_back(flag_name(flag));
    }
  }
  for (const Repeat& repeat : repeats) {
    const Timed& lost = m_field[repeat.request].when;
    const Timed& kept = m_field[repeat.owner].when;
    m_notes.push_back(
        "step " + std::to_string(step + 1) + ": *OUTPUT, FIELD at " + located(lost.where) +
        " (every " + format_real(lost.interval) + " s) asks again for " + joined(repeat.names) +
        " (also requested at " + located(kept.where) + ", every " + format_real(kept.interval) +
        " s): written once, at the finer interval " + format_real(kept.interval) + " s");
  }
}

void OutputSchedule::note_short_intervals(Real dt) {
  if (!(dt > 0.0)) return;
  // Requests split by a second *NODE OUTPUT share their keyword: one note per keyword.
  std::vector<std::string> noted;
  auto note = [&](const Timed& t, const char* kind) {
    const std::string where = located(t.where);
    if (!(t.interval < dt) || std::find(noted.begin(), noted.end(), where) != noted.end()) return;
    noted.push_back(where);
    m_notes.push_back("*OUTPUT, " + std::string(kind) + " at " + where + ": the output interval " +
                      format_real(t.interval) + " s is shorter than the stable increment " +
                      format_real(dt) + " s; output is written once per increment (no more often)");
  };
  for (const FieldRequest& f : m_field) note(f.when, "FIELD");
  for (const Timed& t : m_history) note(t, "HISTORY");
}

bool OutputSchedule::fire(Timed& t, Real step_time, bool last, Real period) {
  // A relative tolerance keeps round-off in the accumulated time from skipping an output.
  const Real tol = 1e-9 * std::max(period, t.interval);
  if (!last && step_time + tol < t.next) return false;
  // Usually one interval is added. A tiny interval (or a huge increment) would need as many
  // additions as intervals were skipped, billions for TIME INTERVAL=1e-20: after a few,
  // jump to the next output time in one product.
  for (int turn = 0; turn < 64 && t.next <= step_time + tol; ++turn) t.next += t.interval;
  if (t.next <= step_time + tol) {
    t.next += (std::floor((step_time + tol - t.next) / t.interval) + 1.0) * t.interval;
    if (t.next <= step_time + tol) t.next += t.interval;  // round-off of the product
  }
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
