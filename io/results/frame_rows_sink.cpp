#include "io/results/frame_rows_sink.hpp"

#include "io/results/results_h5.hpp"

namespace xpl::io {

FrameRowsSink::FrameRowsSink(const std::filesystem::path& h5)
    : m_h5(std::make_unique<ResultsH5>(h5, ResultsH5::FramesOnly{})) {}

FrameRowsSink::~FrameRowsSink() = default;

void FrameRowsSink::begin_run(const Model& model) {
  m_h5->set_units(model.units);
}

void FrameRowsSink::write_frame(const Model& model, const State& state, const FrameFields& fields,
                                const FrameRequest& what) {
  m_h5->write_frame(model, state, fields, what);
}

}  // namespace xpl::io
