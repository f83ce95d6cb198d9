#include "solver/increment/mass_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/forces/element_kinds.hpp"
#include "solver/message_text.hpp"

namespace xpl {

namespace {

bool deformable(const RigidBodies& rigid, Index e) {
  return rigid.element_body().empty() || rigid.element_body()[e] == NO_INDEX;
}

std::string where_text(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line);
}

}  // namespace

MassScalingReport fixed_mass_scaling(const Model& model, const RigidBodies& rigid,
                                     const NodalVectors& reference) {
  MassScalingReport report;
  if (model.steps.empty() || model.steps.front().mass_scaling.empty()) return report;
  const Step& step = model.steps.front();
  const Index n = model.element_count();
  std::vector<Real> factor(static_cast<std::size_t>(n), 1.0), dt(static_cast<std::size_t>(n), 0.0);
  std::vector<Real> element_mass(static_cast<std::size_t>(n), 0.0);  // ρV (solid), ρtA (shell)
  std::vector<Index> all;
  for (Index e = 0; e < n; ++e) {
    if (!deformable(rigid, e)) continue;
    all.push_back(e);
    dt[e] = element_stable_increment(model, e, reference, step.bulk_linear);
    element_mass[e] =
        element_node_mass(model, e, reference) * nodes_per_element(model.element_types[e]);
  }
  Real model_mass = 0.0;  // elements (rigid ones too) and point masses
  for (Index e = 0; e < n; ++e)
    model_mass +=
        element_node_mass(model, e, reference) * nodes_per_element(model.element_types[e]);
  for (const PointInertia& p : model.point_inertias) model_mass += p.mass;
  Real dt_before = std::numeric_limits<Real>::infinity();
  for (Index e : all) dt_before = std::min(dt_before, dt[e]);

  for (const FixedMassScaling& s : step.mass_scaling) {
    std::vector<Index> members;
    if (s.element_set == NO_INDEX) {
      members = all;
    } else {
      for (Index e : model.element_sets[s.element_set].members)
        if (deformable(rigid, e)) members.push_back(e);
    }
    std::vector<Real> before(members.size());
    for (std::size_t k = 0; k < members.size(); ++k) before[k] = factor[members[k]];
    Real set_dt_before = std::numeric_limits<Real>::infinity();
    for (Index e : members) set_dt_before = std::min(set_dt_before, dt[e] * std::sqrt(factor[e]));
    for (Index e : members) factor[e] *= s.factor;
    if (s.dt) {
      if (s.type == FixedMassScaling::Type::BelowMin) {
        for (Index e : members) {
          const Real now = dt[e] * std::sqrt(factor[e]);
          if (now < *s.dt) factor[e] *= (*s.dt / now) * (*s.dt / now);
        }
      } else {
        Real smallest = std::numeric_limits<Real>::infinity();
        for (Index e : members) smallest = std::min(smallest, dt[e] * std::sqrt(factor[e]));
        if (smallest < *s.dt)
          for (Index e : members) factor[e] *= (*s.dt / smallest) * (*s.dt / smallest);
      }
    }
    Real added = 0.0, set_mass = 0.0, set_dt_after = std::numeric_limits<Real>::infinity();
    int scaled = 0;
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Index e = members[k];
      set_mass += before[k] * element_mass[e];
      added += (factor[e] - before[k]) * element_mass[e];
      scaled += factor[e] != before[k] ? 1 : 0;
      set_dt_after = std::min(set_dt_after, dt[e] * std::sqrt(factor[e]));
    }
    const std::string set_name = s.element_set == NO_INDEX
                                     ? std::string("all elements")
                                     : "ELSET=" + model.element_sets[s.element_set].name;
    report.messages.push_back(where_text(s.where) + ": *FIXED MASS SCALING (" + set_name + "): " +
                              std::to_string(scaled) + " of " + std::to_string(members.size()) +
                              " elements scaled; mass added " + format_real(added) +
                              " kg to the set's " + format_real(set_mass) + " kg (+" +
                              format_real(set_mass > 0.0 ? 100.0 * added / set_mass : 0.0) +
                              " %); smallest element increment " + format_real(set_dt_before) +
                              " s -> " + format_real(set_dt_after) + " s");
  }
  Real dt_after = std::numeric_limits<Real>::infinity();
  for (Index e : all) {
    dt_after = std::min(dt_after, dt[e] * std::sqrt(factor[e]));
    report.added_mass += (factor[e] - 1.0) * element_mass[e];
  }
  report.factor = factor;
  const Real percent = model_mass > 0.0 ? 100.0 * report.added_mass / model_mass : 0.0;
  report.messages.push_back("fixed mass scaling: model mass " + format_real(model_mass) +
                            " kg, added " + format_real(report.added_mass) + " kg (+" +
                            format_real(percent) + " %); smallest element increment " +
                            format_real(dt_before) + " s -> " + format_real(dt_after) +
                            " s (before the scale factor)");
  report.summary = "fixed mass scaling: +" + format_real(report.added_mass) + " kg (+" +
                   format_real(percent) + " % of the model mass), smallest element increment " +
                   format_real(dt_before) + " s -> " + format_real(dt_after) + " s";
  return report;
}

}  // namespace xpl
