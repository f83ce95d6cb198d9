#include "solver/output_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace xpl {

const std::vector<std::string>& energy_names() {
  static const std::vector<std::string> names = {"ALLKE", "ALLSE",  "ALLAE", "ALLIE", "ALLVD",
                                                 "ALLWK", "ETOTAL", "ALLFD", "ALLPW"};
  return names;
}

Real energy_value(const Energies& e, int index) {
  switch (index) {
    case 0:
      return e.kinetic;
    case 1:
      return e.strain;
    case 2:
      return e.artificial;
    case 3:
      return e.internal();
    case 4:
      return e.viscous;
    case 5:
      return e.external_work;
    case 7:
      return e.friction;
    case 8:
      return e.contact;
    default:
      return e.total();
  }
}

namespace {

/// Index of the first contact energy (ALLFD, ALLPW) in energy_names().
constexpr int CONTACT_ENERGY_FIRST = 7;

Real interval_of(const OutputRequest& r, Real period, int default_count) {
  if (r.time_interval > 0.0) return r.time_interval;
  const int n = r.number_interval > 0 ? r.number_interval : default_count;
  return period / n;
}

void merge(FrameRequest& into, const FrameRequest& what) {
  into.displacement |= what.displacement;
  into.velocity |= what.velocity;
  into.acceleration |= what.acceleration;
  into.reaction |= what.reaction;
  into.stress |= what.stress;
  into.volume |= what.volume;
  into.thickness |= what.thickness;
  into.contact_stress |= what.contact_stress;
  into.contact_status |= what.contact_status;
  into.contact_force |= what.contact_force;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

void OutputSchedule::begin_step(const Model& model, int step) {
  const Step& s = model.steps[step];
  m_period = s.time_period;
  m_field.clear();
  m_history.clear();
  m_series.clear();
  m_columns.clear();
  const bool shells = model.has_shells();
  for (const OutputRequest& r : s.outputs) {
    if (r.kind == OutputRequest::Kind::Field) {
      FieldRequest f;
      f.when.interval = interval_of(r, m_period, 20);
      f.when.next = f.when.interval;
      // Translations and rotations are written together (as Abaqus does with U and UR).
      f.what.displacement = has(r.node_variables, "U") || has(r.node_variables, "UR");
      f.what.velocity = has(r.node_variables, "V") || has(r.node_variables, "VR");
      f.what.acceleration = has(r.node_variables, "A");
      f.what.reaction = has(r.node_variables, "RF") || has(r.node_variables, "RM");
      f.what.stress = has(r.element_variables, "S") || has(r.element_variables, "MISES");
      f.what.volume = has(r.element_variables, "EVOL");
      // P2: a model without shells has no thickness to compute or write.
      f.what.thickness = shells && has(r.element_variables, "STH");
      f.what.contact_stress = has(r.contact_variables, "CSTRESS");
      f.what.contact_status = has(r.contact_variables, "CSTATUS");
      f.what.contact_force = has(r.contact_variables, "CFORCE");
      m_field.push_back(f);
      continue;
    }
    Timed t;
    t.interval = interval_of(r, m_period, 200);
    t.next = t.interval;
    m_history.push_back(t);
    if (r.energy) {
      const auto& names = energy_names();
      for (int i = 0; i < static_cast<int>(names.size()); ++i) {
        if (!r.energy_variables.empty() && !has(r.energy_variables, names[i])) continue;
        // P2: the contact energies exist only in models with contact.
        if (i >= CONTACT_ENERGY_FIRST && !model.has_contact()) continue;
        m_series.push_back({"energy/" + names[i], 1, {}});
        m_columns.push_back({Quantity::Energy, i, NO_INDEX});
      }
    }
    if (r.node_set == NO_INDEX) continue;
    const NamedSet& set = model.node_sets[r.node_set];
    for (const std::string& var : r.node_variables) {
      // "U" means U1 U2 U3; "U2" one component.
      const std::string base = var.substr(0, var.find_first_of("123"));
      const Quantity q = node_quantity(base, shells);
      for (int c = 0; c < 3; ++c) {
        const std::string name = base + std::to_string(c + 1);
        if (var != base && var != name) continue;
        HistorySeries series{
            "node/" + set.name + "/" + name, static_cast<Index>(set.members.size()), {}};
        for (Index node : set.members) {
          series.node_ids.push_back(model.node_ids[node]);
          m_columns.push_back({q, c, node});
        }
        m_series.push_back(std::move(series));
      }
    }
  }
}

OutputSchedule::Quantity OutputSchedule::node_quantity(const std::string& base, bool shells) {
  if (base == "V") return Quantity::V;
  if (base == "A") return Quantity::A;
  if (base == "RF") return Quantity::RF;
  // Without shells the rotations are not allocated: their history columns hold zeros.
  if (base == "UR") return shells ? Quantity::UR : Quantity::Zero;
  if (base == "VR") return shells ? Quantity::VR : Quantity::Zero;
  if (base == "RM") return shells ? Quantity::RM : Quantity::Zero;
  return Quantity::U;
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
    switch (c.quantity) {
      case Quantity::U:
        row[i] = state.displacement(c.node, c.component);
        break;
      case Quantity::V:
        row[i] = state.velocity(c.node, c.component);
        break;
      case Quantity::A:
        row[i] = state.acceleration(c.node, c.component);
        break;
      case Quantity::RF:
        row[i] = state.reaction(c.node, c.component);
        break;
      case Quantity::UR:
        row[i] = state.rotation(c.node, c.component);
        break;
      case Quantity::VR:
        row[i] = state.angular_velocity(c.node, c.component);
        break;
      case Quantity::RM:
        row[i] = state.reaction_moment(c.node, c.component);
        break;
      case Quantity::Zero:
        row[i] = 0.0;
        break;
      case Quantity::Energy:
        row[i] = energy_value(state.energies, c.component);
        break;
    }
  }
}

}  // namespace xpl
