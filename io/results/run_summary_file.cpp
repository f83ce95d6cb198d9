#include "io/results/run_summary_file.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "solver/output/output_variables.hpp"

// Build description, set for this file by io/results/CMakeLists.txt.
#ifndef XPL_BUILD_TYPE
#define XPL_BUILD_TYPE ""
#endif
#ifndef XPL_BUILD_COMPILER
#define XPL_BUILD_COMPILER ""
#endif
#ifndef XPL_BUILD_CXX_FLAGS
#define XPL_BUILD_CXX_FLAGS ""
#endif
#ifndef XPL_BUILD_NATIVE
#define XPL_BUILD_NATIVE 0
#endif
#ifndef XPL_BUILD_SANITIZE
#define XPL_BUILD_SANITIZE ""
#endif

namespace xpl::io {

namespace {

/// "internal force" → "internal_force": phase names as JSON keys.
std::string key_of(std::string_view name) {
  std::string key(name);
  std::replace(key.begin(), key.end(), ' ', '_');
  return key;
}

JsonValue energies_json(const Energies& e) {
  // The one list of energies (solver/output/output_variables.hpp), every term present for every
  // model so that the summary's layout does not depend on the model.
  JsonValue out = JsonValue::object();
  for (const EnergyVariable& v : ENERGIES) out.set(std::string(v.name), v.value(e));
  return out;
}

JsonValue build_json() {
  JsonValue out = JsonValue::object();
  out.set("type", XPL_BUILD_TYPE);
  out.set("compiler", XPL_BUILD_COMPILER);
  out.set("cxx_flags", XPL_BUILD_CXX_FLAGS);
  out.set("native", XPL_BUILD_NATIVE != 0);
  out.set("timers", XPL_ENABLE_TIMERS != 0);
  out.set("sanitize", XPL_BUILD_SANITIZE);
  return out;
}

}  // namespace

void SummaryRecord::add_status(const StatusLine& line) {
  const Energies& e = line.energies;
  if (!has_energies) {
    m_initial_total = e.total();
    first_increment = line.dt;
  }
  has_energies = true;
  increments = line.increment;
  simulated_time = line.total_time;
  last_increment = line.dt;
  energies = e;
  if (m_solver_drift) return;
  energy_scale = std::max({energy_scale, e.kinetic, e.internal(), std::abs(e.external_work)});
  const Real drift = std::abs(e.total() - m_initial_total);
  if (drift > energy_error || !std::isfinite(drift)) {
    energy_error = drift;
    energy_error_time = line.total_time;
  }
  relative_error = energy_scale > 0.0 ? energy_error / energy_scale : 0.0;
}

void SummaryRecord::set_drift(const BalanceDrift& drift) {
  m_solver_drift = true;
  energy_error = std::abs(drift.drift);
  energy_scale = drift.scale;
  relative_error = drift.fraction;
  energy_error_time = drift.time;
}

JsonValue SummaryRecord::json() const {
  JsonValue out = JsonValue::object();
  out.set("format", SUMMARY_FORMAT);
  out.set("job", job);
  out.set("status", status);
  out.set("exit_reason", exit_reason);
  out.set("xpl_version", XPL_VERSION);
  out.set("build", build_json());
  JsonValue& model = out.set("model", JsonValue::object());
  model.set("nodes", static_cast<long>(nodes));
  model.set("elements", static_cast<long>(elements));
  model.set("steps", steps);
  JsonValue& labels = out.set("units", JsonValue::object());
  labels.set("system", units.system_name());
  labels.set("stated", units.stated != nullptr);
  labels.set("description", units.explanation.empty() ? units.summary() : units.explanation);
  for (const auto& [key, si] : {std::pair<const char*, const char*>{"length", "m"},
                                {"mass", "kg"},
                                {"time", "s"},
                                {"force", "N"},
                                {"stress", "Pa"},
                                {"energy", "J"}})
    labels.set(key, units.label(si));
  out.set("threads", threads);
  out.set("steps_started", steps_started);
  out.set("increments", increments);
  out.set("simulated_time", simulated_time);
  out.set("first_increment", first_increment);
  out.set("last_increment", last_increment);
  JsonValue& wall = out.set("wall_time", JsonValue::object());
  for (int p = 0; p < static_cast<int>(Phase::COUNT); ++p) {
    const auto phase = static_cast<Phase>(p);
    wall.set(key_of(phase_name(phase)), timers.seconds(phase));
  }
  wall.set("phases_total", timers.total());
  wall.set("elapsed", elapsed_seconds);
  out.set("element_cycles_per_second", element_cycles_per_second);
  out.set("peak_memory_mb", peak_memory_mb());
  out.set("energies", energies_json(energies));
  JsonValue& balance = out.set("energy_balance", JsonValue::object());
  balance.set("max_error", energy_error);
  balance.set("relative_error", relative_error);
  balance.set("time", energy_error_time);
  balance.set("energy_scale", energy_scale);
  if (distribution) {
    const DistributionSummary& d = *distribution;
    JsonValue& mpi = out.set("mpi", JsonValue::object());
    mpi.set("ranks", static_cast<long>(d.ranks.size()));
    mpi.set("method", d.method);
    mpi.set("imbalance", d.imbalance);
    mpi.set("interface_nodes", static_cast<long>(d.interface_nodes));
    mpi.set("cut_edges", d.cut_edges);
    mpi.set("frames", d.shared_frames ? "every rank its rows" : "gathered to rank 0");
    mpi.set("times", d.times_gathered ? "gathered" : "not gathered: the run failed");
    // One object per rank, keyed by its number: /summary stores objects only.
    JsonValue& ranks = mpi.set("rank", JsonValue::object());
    for (std::size_t r = 0; r < d.ranks.size(); ++r) {
      const DistributionSummary::Rank& k = d.ranks[r];
      JsonValue& rank = ranks.set(std::to_string(r), JsonValue::object());
      rank.set("elements", static_cast<long>(k.elements));
      rank.set("owned_nodes", static_cast<long>(k.owned_nodes));
      rank.set("interface_nodes", static_cast<long>(k.interface_nodes));
      rank.set("neighbours", static_cast<long>(k.neighbours));
      if (!d.times_gathered) continue;
      rank.set("time_loop", k.time_loop);
      rank.set("compute", k.compute);
      rank.set("exchange", k.exchange);
      rank.set("wait", k.wait);
      rank.set("output", k.output);
      rank.set("contact_search", k.contact_search);
      rank.set("contact_force", k.contact_force);
      rank.set("contact_exchange", k.contact_exchange);
      rank.set("contact_values", k.contact_values);
      rank.set("contact_values_whole", k.contact_values_whole);
      rank.set("contact_values_sent", k.contact_values_sent);
      rank.set("contact_build_received", k.contact_build_received);
      rank.set("contact_build_sent", k.contact_build_sent);
      rank.set("contact_lists_received", k.contact_lists_received);
      rank.set("contact_lists_sent", k.contact_lists_sent);
      rank.set("tie_values", k.tie_values);
      rank.set("tie_values_sent", k.tie_values_sent);
      rank.set("tie_values_whole", k.tie_values_whole);
      rank.set("contact_slot_received", k.contact_slot_received);
      rank.set("contact_slot_sent", k.contact_slot_sent);
    }
  }
  return out;
}

double peak_memory_mb() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0.0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

void write_summary_json(const std::filesystem::path& path, const JsonValue& summary) {
  std::filesystem::path temporary = path;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << summary.text();
    out.flush();
  }
  std::error_code error;
  if (std::filesystem::file_size(temporary, error) == 0 || error) {
    std::filesystem::remove(temporary, error);  // a full disk leaves no stray file
    throw std::runtime_error("cannot write " + temporary.string());
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("cannot write " + path.string());
  }
}

std::filesystem::path summary_path(const std::filesystem::path& h5) {
  std::filesystem::path path = h5;
  path.replace_extension(".summary.json");
  return path;
}

}  // namespace xpl::io
