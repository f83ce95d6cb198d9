#include "io/results/results_history.hpp"

#include <stdexcept>
#include <string>

namespace xpl::io {

namespace {

/// Checks a series path: relative, no empty components, not clashing with `time`.
void check_series_path(const std::string& path, int step) {
  const bool bad = path.empty() || path == "time" || path.front() == '/' || path.back() == '/' ||
                   path.find("//") != std::string::npos;
  if (bad) {
    throw std::invalid_argument("history of step " + std::to_string(step) +
                                ": invalid series path '" + path + "'");
  }
}

}  // namespace

void HistoryWriter::begin(hid_t file, int step, const std::vector<HistorySeries>& series,
                          const ModelUnits& units) {
  if (pending()) throw std::logic_error("HistoryWriter::begin: rows of the last step not written");
  end();
  m_step = step;
  const std::string group = "history/step_" + std::to_string(step);
  h5::require_group(file, group);
  m_time.emplace(file, group + "/time", 0);
  h5::set_string_attribute(m_time->open(file).get(), "units", units.label("s"));
  m_columns.clear();
  m_row_width = 0;
  for (const HistorySeries& s : series) {
    check_series_path(s.path, step);
    if (s.width < 1) {
      throw std::invalid_argument("history series " + s.path + ": width must be at least 1");
    }
    if (!s.node_ids.empty() && static_cast<Index>(s.node_ids.size()) != s.width) {
      throw std::invalid_argument("history series " + s.path + ": " +
                                  std::to_string(s.node_ids.size()) + " node ids for width " +
                                  std::to_string(s.width));
    }
    const auto slash = s.path.rfind('/');
    // Node series are always (nt, n_nodes), also for a one-node set; whole-model series (nt).
    const hsize_t width = s.width > 1 || !s.node_ids.empty() ? static_cast<hsize_t>(s.width) : 0;
    if (slash != std::string::npos) h5::require_group(file, group + "/" + s.path.substr(0, slash));
    m_series.emplace_back(file, group + "/" + s.path, width);
    const h5::Handle dataset = m_series.back().open(file);
    if (!s.node_ids.empty()) {
      h5::set_int64_array_attribute(dataset.get(), "node_ids", s.node_ids);
    }
    // Issue 19: what the columns are (node series: this component of node node_ids[j]).
    if (!s.component.empty()) h5::set_string_attribute(dataset.get(), "components", s.component);
    if (!s.unit.empty()) h5::set_string_attribute(dataset.get(), "units", units.label(s.unit));
    m_columns.push_back(m_row_width);
    m_row_width += static_cast<hsize_t>(s.width);
  }
  m_times.reserve(ROWS_PER_WRITE);
  m_values.reserve(ROWS_PER_WRITE * m_row_width);
}

bool HistoryWriter::append(Real time, std::span<const Real> values) {
  if (!active()) throw std::logic_error("append_history before the history was declared");
  if (values.size() != m_row_width) {
    throw std::invalid_argument("history row of step " + std::to_string(m_step) + " has " +
                                std::to_string(values.size()) + " values; " +
                                std::to_string(m_row_width) + " columns were declared");
  }
  m_times.push_back(time);
  m_values.insert(m_values.end(), values.begin(), values.end());
  return m_times.size() >= ROWS_PER_WRITE;
}

void HistoryWriter::write_pending(hid_t file) {
  if (!active() || m_times.empty()) return;
  const auto rows = static_cast<hsize_t>(m_times.size());
  m_time->append(file, m_times.data(), rows, 1, 0);
  for (std::size_t i = 0; i < m_series.size(); ++i) {
    m_series[i].append(file, m_values.data(), rows, m_row_width, m_columns[i]);
  }
  m_times.clear();
  m_values.clear();
}

void HistoryWriter::end() {
  m_series.clear();
  m_time.reset();
  m_times.clear();
  m_values.clear();
}

}  // namespace xpl::io
