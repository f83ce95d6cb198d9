#include "io/results/results_log.hpp"

#include <cstdio>
#include <ctime>
#include <stdexcept>

#include "common/error.hpp"
#include "io/results/results_mesh.hpp"

#ifndef XPL_VERSION
#define XPL_VERSION "unknown"
#endif

namespace xpl::io {

namespace {

std::ofstream open_log(const std::filesystem::path& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot create " + path.string());
  return out;
}

std::string now_text() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%S", &local);
  return text;
}

void write_header(std::ofstream& out, const char* kind, const std::string& job) {
  out << " xpl " << XPL_VERSION << " " << kind << "\n JOB  " << escape_control(job) << "\n DATE "
      << now_text() << "\n\n";
  out.flush();
}

/// printf into a std::string (the fixed columns are easiest to get right with printf).
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

/// The table of seconds per phase and the element-cycles per second.
void write_timings(std::ofstream& out, const PhaseTimers& timers, double cycles_per_second) {
  out << "\n WALL CLOCK TIME PER PHASE\n";
  for (int p = 0; p < static_cast<int>(Phase::COUNT); ++p) {
    const auto phase = static_cast<Phase>(p);
    out << format("   %-20s %12.3f s\n", std::string(phase_name(phase)).c_str(),
                  timers.seconds(phase));
  }
  out << format("   %-20s %12.3f s\n", "total", timers.total());
  out << format(" ELEMENT-CYCLES PER SECOND %12.4E\n", cycles_per_second);
}

/// How material `m`'s plasticity reads in the model summary: initial yield stress, hardening
/// form and rate dependence, one line each.
void write_plasticity(std::ofstream& out, const Material& m) {
  const elements::Plasticity& p = *m.plastic;
  out << format("     %s: initial yield stress %.4E\n", m.name.c_str(), p.initial_yield());
  if (p.hardening == elements::Hardening::JohnsonCook) {
    out << format("       hardening Johnson-Cook A + B*PEEQ^n: A %.4E, B %.4E, n %g\n", p.jc_a,
                  p.jc_b, p.jc_n);
    out << format(
        "       thermal term taken as 1 (no temperature field): m %g, melt %g, "
        "transition %g\n",
        p.jc_m, p.jc_melt, p.jc_transition);
  } else {
    const std::size_t n = p.yield_stress.size();
    if (n == 1)
      out << "       hardening none: perfectly plastic\n";
    else
      out << format(
          "       hardening tabular isotropic: %zu points to PEEQ %g (yield %.4E), "
          "constant beyond\n",
          n, p.plastic_strain.back(), p.yield_stress.back());
    if (p.softens()) out << "       the table softens: the yield stress falls with PEEQ\n";
  }
  switch (p.rate) {
    case elements::RateDependence::None:
      out << "       rate dependence none\n";
      break;
    case elements::RateDependence::PowerLaw:
      out << format(
          "       rate dependence power law (Cowper-Symonds) 1 + (rate/D)^(1/n): "
          "D %g 1/s, n %g\n",
          p.power_d, p.power_n);
      break;
    case elements::RateDependence::JohnsonCook:
      out << format(
          "       rate dependence Johnson-Cook 1 + C ln(rate/rate0): C %g, rate0 %g "
          "1/s\n",
          p.rate_c, p.rate_reference);
      break;
  }
}

}  // namespace

const char* completion_text(RunStatus status) {
  switch (status) {
    case RunStatus::Completed:
      return "THE ANALYSIS HAS COMPLETED SUCCESSFULLY";
    case RunStatus::Checked:
      return "DATA CHECK COMPLETED";
    case RunStatus::Failed:
      return "THE ANALYSIS HAS NOT BEEN COMPLETED";
    case RunStatus::Interrupted:
      return "THE ANALYSIS HAS BEEN INTERRUPTED";
  }
  return "";
}

StaFile::StaFile(const std::filesystem::path& path, const std::string& job)
    : m_out(open_log(path)) {
  write_header(m_out, "STATUS FILE", job);
}

void StaFile::begin_step(int step, const std::string& name) {
  m_out << "\n STEP " << step << "  " << escape_control(name) << "\n\n"
        << "  STEP  INCREMENT   TOTAL TIME    STEP TIME       STABLE     CRITICAL     GOVERNED"
           "      KINETIC        TOTAL    WALL TIME\n"
        << "                                              INCREMENT      ELEMENT           BY"
           "       ENERGY       ENERGY          (s)\n";
  m_out.flush();
}

void StaFile::note(const std::string& text) {
  m_out << " " << escape_control(text) << "\n";
  m_out.flush();
}

void StaFile::line(int step, const StatusLine& line, double wall) {
  // A contact penalty that limits the increment shows as "node N" in the critical column.
  const std::string critical = line.critical_contact_node != 0
                                   ? "node " + std::to_string(line.critical_contact_node)
                                   : std::to_string(static_cast<long long>(line.critical_element));
  // GOVERNED BY: what sets the increment (increment_control.hpp), one word.
  m_out << format("%6d %10ld %12.4E %12.4E %12.4E %12s %12s %12.4E %12.4E %12.2f\n", step,
                  line.increment, line.total_time, line.step_time, line.dt, critical.c_str(),
                  line.governing.c_str(), line.energies.kinetic, line.energies.total(), wall);
  m_out.flush();
}

void StaFile::finish(RunStatus status, const std::string& error, const PhaseTimers& timers,
                     double element_cycles_per_second) {
  m_out << "\n " << completion_text(status) << "\n";
  if (!error.empty()) m_out << " " << escape_control(error) << "\n";
  write_timings(m_out, timers, element_cycles_per_second);
  m_out.flush();
}

MsgFile::MsgFile(const std::filesystem::path& path, const std::string& job)
    : m_out(open_log(path)) {
  write_header(m_out, "MESSAGE FILE", job);
}

void MsgFile::summary(const Model& model) {
  m_out << " MODEL SUMMARY\n";
  if (!model.heading.empty()) m_out << "   heading: " << escape_control(model.heading) << "\n";
  // The numbers are the deck's: say which units they are in (common/units.hpp).
  m_out << "   units: "
        << escape_control(model.units.explanation.empty() ? model.units.summary()
                                                          : model.units.explanation)
        << "\n";
  m_out << format("   %-28s %10d\n", "nodes", model.node_count());
  m_out << format("   %-28s %10d\n", "elements", model.element_count());
  for (ElementType type : {ElementType::C3D8R, ElementType::C3D8, ElementType::S4R}) {
    long count = 0;
    for (ElementType t : model.element_types) count += t == type ? 1 : 0;
    if (count > 0) {
      m_out << format("     %-26s %10ld\n", element_type_name(type), count);
    }
  }
  const auto line = [&](const char* what, std::size_t n) {
    m_out << format("   %-28s %10zu\n", what, n);
  };
  line("materials", model.materials.size());
  std::size_t plastic = 0;
  for (const Material& m : model.materials) plastic += m.plastic ? 1 : 0;
  if (plastic > 0) {
    line("  plastic (J2, isotropic)", plastic);
    for (const Material& m : model.materials)
      if (m.plastic) write_plasticity(m_out, m);
  }
  line("solid sections", model.solid_sections.size());
  if (!model.shell_sections.empty()) line("shell sections", model.shell_sections.size());
  line("node sets", model.node_sets.size());
  line("element sets", model.element_sets.size());
  line("surfaces", model.surfaces.size());
  line("amplitudes", model.amplitudes.size());
  line("steps", model.steps.size());
  m_out << "\n";
  m_out.flush();
}

void MsgFile::begin_step(const Model& model, int step) {
  m_out << "\n STEP " << step + 1;
  const auto index = static_cast<std::size_t>(step);
  if (index < model.steps.size()) {
    const Step& s = model.steps[index];
    m_out << "  " << escape_control(s.name) << "\n"
          << format("   time period %12.4E s\n", s.time_period);
    if (s.increment.fixed) m_out << format("   fixed increment %12.4E s\n", *s.increment.fixed);
    m_out << format("   time scale factor %g, bulk viscosity %g %g\n", s.increment.scale_factor,
                    s.bulk_linear, s.bulk_quadratic);
  } else {
    m_out << "\n";
  }
  m_out << "\n";
  m_out.flush();
}

void MsgFile::message(Severity severity, const std::string& message) {
  const std::string text = escape_control(message);
  switch (severity) {
    case Severity::Info:
      m_out << " " << text << "\n";
      break;
    case Severity::Note:
      m_out << "***NOTE: " << text << "\n";
      break;
    case Severity::Warning:
      m_out << "***WARNING: " << text << "\n";
      break;
    case Severity::Error:
      m_out << "***ERROR: " << text << "\n";
      break;
  }
  m_out.flush();
}

void MsgFile::finish(RunStatus status, const std::string& error, const PhaseTimers& timers,
                     double element_cycles_per_second) {
  m_out << "\n " << completion_text(status) << "\n";
  if (!error.empty())
    m_out << (status == RunStatus::Interrupted ? "***NOTE: " : "***ERROR: ")
          << escape_control(error) << "\n";
  write_timings(m_out, timers, element_cycles_per_second);
  m_out.flush();
}

}  // namespace xpl::io
