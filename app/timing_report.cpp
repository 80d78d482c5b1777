#include "app/timing_report.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

namespace mane::app {

double allPassesMilliseconds(const std::vector<render::PassTiming>& frame) {
  double end = 0.0;
  for (const auto& timing : frame) end = std::max(end, timing.startMilliseconds + timing.milliseconds);
  return end;
}

std::vector<PassStatistics> passStatistics(const std::vector<std::vector<render::PassTiming>>& frames) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> samples;
  const std::string span = "all passes";
  for (const auto& frame : frames) {
    for (const auto& timing : frame) {
      const std::string pass(timing.pass.name());
      if (!samples.contains(pass)) order.push_back(pass);
      samples[pass].push_back(timing.milliseconds);
    }
    if (!frame.empty()) samples[span].push_back(allPassesMilliseconds(frame));
  }
  if (samples.contains(span)) order.push_back(span);
  std::vector<PassStatistics> result;
  for (const auto& pass : order) {
    auto& values = samples[pass];
    std::sort(values.begin(), values.end());
    result.push_back({pass, values[values.size() / 2], values.back()});
  }
  return result;
}

void printTimingTable(const std::vector<PassStatistics>& statistics) {
  std::printf("%-18s %10s %10s\n", "pass", "median ms", "worst ms");
  for (const auto& row : statistics) std::printf("%-18s %10.2f %10.2f\n", row.pass.c_str(), row.medianMs, row.worstMs);
}

}  // namespace mane::app
