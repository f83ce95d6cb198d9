#include "io/results/results_h5.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "io/results/results_frame.hpp"
#include "io/results/results_mesh.hpp"

namespace xpl::io {

namespace {

#ifndef XPL_VERSION
#define XPL_VERSION "unknown"
#endif

/// Writes the status attributes of the open `file`.
void write_status(hid_t file, const std::string& status, const std::string& error,
                  std::optional<double> time_reached) {
  h5::set_string_attribute(file, "status", status);
  h5::set_string_attribute(file, "error", error);
  if (time_reached) h5::set_real_attribute(file, "time_reached", *time_reached);
}

}  // namespace

ResultsH5::ResultsH5(const std::filesystem::path& path, FramesOnly) : m_path(path.string()) {
  h5::silence_errors();
}

void ResultsH5::set_units(const ModelUnits& units) {
  m_units = units;
}

ResultsH5::ResultsH5(const std::filesystem::path& path, const std::string& job)
    : m_path(path.string()) {
  h5::silence_errors();
  m_access =
      h5::Handle{h5::check_id(H5Pcreate(H5P_FILE_ACCESS), "cannot create properties"), H5Pclose};
  // The 1.8 format stores attributes larger than 64 KiB (node_ids of wide history series). It
  // also has no "open for writing" flag in the superblock, which would make a file whose
  // writer was killed unreadable until h5clear.
  h5::check(H5Pset_libver_bounds(m_access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
            "cannot set the file format");
  // Closing the file closes every object still open in it: no handle kept by mistake can
  // keep the file, and its lock, open between writes.
  h5::check(H5Pset_fclose_degree(m_access.get(), H5F_CLOSE_STRONG), "cannot set the close mode");
  // A reader (ParaView, h5py) may still hold the previous run's file open: unlink it rather
  // than truncate it, so that the new run does not wait for the reader's lock and the reader
  // keeps the old, complete file. JOB.lck (job_lock.hpp) keeps one run per job and directory.
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  h5::Handle file{
      h5::check_id(H5Fcreate(m_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, m_access.get()),
                   "cannot create " + m_path),
      H5Fclose};
  h5::set_string_attribute(file.get(), "xpl_version", XPL_VERSION);
  h5::set_string_attribute(file.get(), "job", job);
  h5::set_string_attribute(file.get(), "heading", "");
  h5::set_string_attribute(file.get(), "status", "running");
  h5::set_string_attribute(file.get(), "error", "");
  h5::check(H5Fclose(file.release()), "cannot close " + m_path);
}

void ResultsH5::with_file(const std::function<void(hid_t)>& write) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto waited = [&start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  hid_t id = -1;
  for (int attempt = 0;; ++attempt) {
    id = H5Fopen(m_path.c_str(), H5F_ACC_RDWR, m_access.get());
    if (id >= 0) break;
    // HDF5's lock: a reader has the file open; wait for it. Anything else fails now.
    if (!h5::lock_refused()) h5::fail("cannot open " + m_path + " for writing");
    if (waited() > LOCK_WAIT) {
      h5::fail("cannot open " + m_path + " for writing: another process kept it open for " +
               std::to_string(static_cast<int>(LOCK_WAIT)) +
               " s (readers must close it between reads)");
    }
    H5Eclear2(H5E_DEFAULT);
    std::this_thread::sleep_for(std::chrono::milliseconds(std::min(1 << std::min(attempt, 6), 50)));
  }
  h5::Handle file{id, H5Fclose};
  if (const double seconds = waited(); seconds > LOCK_NOTICE && m_wait_notice) {
    char duration[32];
    std::snprintf(duration, sizeof duration, "%.1f s", seconds);
    m_wait_notice("the run waited " + std::string(duration) +
                  " for another process (a reader) to close " + m_path);
  }
  write(id);
  h5::check(H5Fflush(id, H5F_SCOPE_GLOBAL), "cannot flush " + m_path);
  h5::check(H5Fclose(file.release()), "cannot close " + m_path);
}

XdmfMesh ResultsH5::write_mesh(const Model& model) {
  XdmfMesh mesh;
  m_units = model.units;
  with_file([&](hid_t file) {
    h5::set_string_attribute(file, "heading", model.heading);
    // The numbers are the deck's; these say in which units (common/units.hpp).
    h5::set_string_attribute(file, "unit_system", m_units.system_name());
    h5::set_string_attribute(file, "units",
                             m_units.explanation.empty() ? m_units.summary() : m_units.explanation);
    mesh = write_mesh_group(file, model);
    const h5::Handle coordinates{h5::check_id(H5Dopen2(file, "mesh/coordinates", H5P_DEFAULT),
                                              "cannot open /mesh/coordinates"),
                                 H5Dclose};
    h5::set_string_attribute(coordinates.get(), "units", m_units.label("m"));
  });
  return mesh;
}

void ResultsH5::begin_step(int step) {
  if (m_history.pending()) with_file([&](hid_t file) { m_history.write_pending(file); });
  m_history.end();
  m_step = step;
}

void ResultsH5::declare_history(const std::vector<HistorySeries>& series) {
  if (m_history.active()) {
    throw std::logic_error("declare_history called twice in step " + std::to_string(m_step + 1));
  }
  with_file([&](hid_t file) { m_history.begin(file, m_step + 1, series, m_units); });
}

void ResultsH5::append_history(Real time, std::span<const Real> values) {
  if (m_history.append(time, values)) with_file([&](hid_t file) { m_history.write_pending(file); });
}

std::string ResultsH5::write_frame(const Model& model, const State& state,
                                   const FrameFields& fields, const FrameRequest& what) {
  check_frame(model, state, fields, what);
  char name[16];
  std::snprintf(name, sizeof name, "%06d", m_frames);
  const auto write = [&](hid_t file) {
    const h5::Handle group = h5::require_group(file, std::string("frames/") + name);
    const hid_t g = group.get();
    h5::set_real_attribute(g, "time", state.time);
    h5::set_real_attribute(g, "step_time", state.step_time);
    h5::set_int64_attribute(g, "step", state.step + 1);
    const auto step_index = static_cast<std::size_t>(state.step);
    h5::set_string_attribute(g, "step_name",
                             step_index < model.steps.size() ? model.steps[step_index].name : "");
    h5::set_int64_attribute(g, "increment", state.increment);

    write_frame_datasets(file, g, name, model, state, fields, what, m_units);
  };
  if (fields.rows.collective) {
    // Every rank its rows, together; the history rows up to the frame first, by this rank
    // alone (the others hold none).
    if (m_history.pending()) with_file([&](hid_t file) { m_history.write_pending(file); });
    with_shared_file(write);
  } else {
    with_file([&](hid_t file) {
      // The history rows up to the frame go with it: a reader sees both up to the same time.
      m_history.write_pending(file);
      write(file);
    });
  }
  ++m_frames;
  return name;
}

void ResultsH5::with_shared_file(const std::function<void(hid_t)>& write) {
#ifdef H5_HAVE_PARALLEL
  // Every rank of MPI_COMM_WORLD opens the file with MPI-IO, makes the same metadata calls
  // (groups, datasets, attributes: collective in parallel HDF5) and writes its rows
  // (h5::write_real_rows). No lock to wait for: the MPI-IO driver takes none.
  const h5::Handle access{h5::check_id(H5Pcreate(H5P_FILE_ACCESS), "cannot create properties"),
                          H5Pclose};
  h5::check(H5Pset_fapl_mpio(access.get(), MPI_COMM_WORLD, MPI_INFO_NULL),
            "cannot set MPI-IO access");
  h5::check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
            "cannot set the file format");
  h5::Handle file{h5::check_id(H5Fopen(m_path.c_str(), H5F_ACC_RDWR, access.get()),
                               "cannot open " + m_path + " for writing with MPI-IO"),
                  H5Fclose};
  write(file.get());
  h5::check(H5Fclose(file.release()), "cannot close " + m_path);
#else
  (void)write;
  throw std::logic_error("a frame written by every rank needs the parallel HDF5 (XPL_MPI=ON)");
#endif
}

std::string ResultsH5::with_length_unit(const std::string& text) const {
  const std::string length = m_units.label("m");
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const bool alone =
        text[i] == 'm' && (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1]))) &&
        (i + 1 == text.size() || !std::isalnum(static_cast<unsigned char>(text[i + 1])));
    out += alone ? length : std::string(1, text[i]);
  }
  return out;
}

void ResultsH5::write_table(const ResultTable& table) {
  with_file([&](hid_t file) {
    const h5::Handle group = h5::require_group(file, table.path);
    if (!table.description.empty())
      h5::set_string_attribute(group.get(), "description", table.description);
    h5::set_int64_attribute(group.get(), "rows", table.rows);
    for (const auto& [name, value] : table.attributes)
      h5::set_string_attribute(group.get(), name, value);
    for (const TableColumn& c : table.columns) {
      const std::vector<hsize_t> dims = c.width == 1
                                            ? std::vector<hsize_t>{static_cast<hsize_t>(table.rows)}
                                            : std::vector<hsize_t>{static_cast<hsize_t>(table.rows),
                                                                   static_cast<hsize_t>(c.width)};
      if (c.integer)
        h5::write_int64(group.get(), c.name, c.ids, dims);
      else
        h5::write_real(group.get(), c.name, c.values, dims);
      if (!c.description.empty()) {
        const h5::Handle data =
            h5::Handle(h5::check_id(H5Dopen2(group.get(), c.name.c_str(), H5P_DEFAULT),
                                    "cannot open " + c.name),
                       H5Dclose);
        // The solver describes lengths in m (SI): in the model's units instead.
        h5::set_string_attribute(data.get(), "description",
                                 c.integer ? c.description : with_length_unit(c.description));
      }
    }
  });
}

void ResultsH5::finish(const std::string& status, const std::string& error,
                       std::optional<double> time_reached) {
  // The last history rows and the status in one write: a reader that sees "completed" sees
  // the whole history.
  with_file([&](hid_t file) {
    m_history.write_pending(file);
    write_status(file, status, error, time_reached);
  });
  m_history.end();
}

void ResultsH5::record_status(const std::string& status, const std::string& error,
                              std::optional<double> time_reached) {
  with_file([&](hid_t file) { write_status(file, status, error, time_reached); });
}

void ResultsH5::write_summary(const JsonValue& summary) {
  with_file([&](hid_t file) {
    const h5::Handle group = h5::require_group(file, "summary");
    const auto write = [&](const auto& self, const JsonValue& value,
                           const std::string& key) -> void {
      if (const auto* members = value.as_object()) {
        for (const auto& [name, member] : *members)
          self(self, member, key.empty() ? name : key + "." + name);
      } else if (const bool* b = value.as_bool()) {
        h5::set_int64_attribute(group.get(), key, *b ? 1 : 0);
      } else if (const std::int64_t* i = value.as_int()) {
        h5::set_int64_attribute(group.get(), key, *i);
      } else if (const double* d = value.as_double()) {
        h5::set_real_attribute(group.get(), key, *d);
      } else if (const std::string* s = value.as_string()) {
        h5::set_string_attribute(group.get(), key, *s);
      } else if (value.is_null()) {
        h5::set_real_attribute(group.get(), key, std::nan(""));
      }
      // Arrays: the summary has none.
    };
    write(write, summary, "");
  });
}

}  // namespace xpl::io
