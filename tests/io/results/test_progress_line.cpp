#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "io/results/progress_line.hpp"

using xpl::StatusLine;
using xpl::io::ProgressMeter;

namespace {

StatusLine status(long increment, double step_time, double total_time, double dt) {
  StatusLine line;
  line.increment = increment;
  line.step_time = step_time;
  line.total_time = total_time;
  line.dt = dt;
  return line;
}

}  // namespace

TEST_CASE("wall-clock times read as m:ss or h:mm:ss", "[io][progress]") {
  CHECK(xpl::io::clock_text(0.0) == "0:00");
  CHECK(xpl::io::clock_text(12.4) == "0:12");
  CHECK(xpl::io::clock_text(59.6) == "1:00");
  CHECK(xpl::io::clock_text(3599.0) == "59:59");
  CHECK(xpl::io::clock_text(3723.0) == "1:02:03");
  CHECK(xpl::io::clock_text(-1.0) == "--:--");
}

TEST_CASE("the progress line gives elapsed time, rate and an ETA from the simulated time",
          "[io][progress]") {
  // Two steps of 1 ms and 3 ms: 4 ms in all.
  ProgressMeter meter(4e-3, 2, "s");
  const std::string first = meter.text(status(0, 0.0, 0.0, 1e-7), 1, 1e-3, 0.3);
  CHECK(first.find("step 1/2") == 0);
  CHECK(first.find("ETA --:--") != std::string::npos);  // no rate yet
  // 10 s later: 1000 increments and 1 ms simulated (the whole first step): 100 inc/s and
  // 1e-4 simulated s per s, so the 3 ms left take 30 s.
  const std::string text = meter.text(status(1000, 1e-3, 1e-3, 1e-6), 1, 1e-3, 10.3);
  INFO(text);
  const std::regex format(
      R"(step 1/2  t = 1\.0000e-03 of 1\.0000e-03 s \(100\.0%\)  increment 1000  dt 1\.000e-06 s)"
      R"(  elapsed 0:10  100 inc/s  ETA 0:30)");
  CHECK(std::regex_match(text, format));
  // In the second step, halfway through the run's simulated time after 20 s: ETA 20 s.
  const std::string later = meter.text(status(2000, 1e-3, 2e-3, 1e-6), 2, 3e-3, 20.3);
  INFO(later);
  CHECK(later.find("step 2/2") == 0);
  CHECK(later.find("( 33.3%)") != std::string::npos);
  CHECK(later.find("ETA 0:20") != std::string::npos);
  // The deck's time unit labels the times.
  ProgressMeter ms(1.0, 1, "ms");
  CHECK(ms.text(status(0, 0.5, 0.5, 1e-4), 1, 1.0, 0.0).find("of 1.0000e+00 ms") !=
        std::string::npos);
}
