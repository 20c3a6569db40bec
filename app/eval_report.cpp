#include "app/eval_report.h"

#include "app/cli_common.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace strata {
namespace {
std::string mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

std::string formatReportText(const EvalResult& r, const ReportContext& c, bool listNodes) {
  std::ostringstream out;
  const std::string u = unitAbbreviation(c.unit);
  char line[256];
  out << "input     " << c.input << "  (tree depth " << c.treeDepth << ")\n";
  out << "backend   " << r.backend << "\n";
  std::snprintf(line, sizeof(line), "grid      %d x %d x %d cells, h = %.6g %s\n", r.grid.cells.x,
                r.grid.cells.y, r.grid.cells.z, r.grid.h, u.c_str());
  out << line;
  out << "\nstage        seconds   nodes      surfels   peak memory\n";
  for (const StageStats& s : r.stages) {
    std::snprintf(line, sizeof(line), "%-10s %9.4f %7d %12llu   %s\n", s.name.c_str(), s.seconds,
                  s.runs, static_cast<unsigned long long>(s.surfels), mib(s.peakBytes).c_str());
    out << line;
  }
  std::snprintf(line, sizeof(line), "%-10s %9.4f %7s %12s   %s\n", "total", r.seconds, "", "",
                mib(r.peakBytes).c_str());
  out << line;
  std::snprintf(line, sizeof(line),
                "\nnodes     %d computed, %d reused from the cache (%s cached)\n", r.computed,
                r.reused, mib(r.cacheBytes).c_str());
  out << line;
  if (listNodes) {
    for (const NodeRecord& n : r.nodes) {
      std::snprintf(line, sizeof(line), "  %-24s %-12s %-12s %9.4f s %12llu surfels\n",
                    n.name.c_str(), n.kind.c_str(), outcomeName(n.outcome), n.seconds,
                    static_cast<unsigned long long>(n.surfels));
      out << line;
    }
  }
  std::snprintf(line, sizeof(line),
                "result    volume %.6g %s^3 (axes %.6g / %.6g / %.6g), area %.6g %s^2, %zu "
                "surfels\n",
                r.measure.volume, u.c_str(), r.measure.axisVolume[0], r.measure.axisVolume[1],
                r.measure.axisVolume[2], r.measure.area, u.c_str(), r.measure.surfels);
  out << line;
  if (std::isfinite(r.measure.thinnestWall)) {
    std::snprintf(line, sizeof(line),
                  "          thinnest wall about %.4g %s (%.2g cells) at (%.4g, %.4g, %.4g)\n",
                  r.measure.thinnestWall, u.c_str(), r.measure.thinnestWall / r.grid.h,
                  r.measure.thinnestAt.x, r.measure.thinnestAt.y, r.measure.thinnestAt.z);
    out << line;
  }
  if (!c.output.empty()) out << "wrote     " << c.output << " (" << c.outputPoints << " points)\n";
  out << warningLines(c.warnings);
  return out.str();
}

std::string formatReportJson(const EvalResult& r, const ReportContext& c) {
  nlohmann::ordered_json j;
  j["input"] = c.input;
  j["unit"] = c.unit;
  j["backend"] = r.backend;
  j["tree_depth"] = c.treeDepth;
  j["resolution"] = std::max({r.grid.cells.x, r.grid.cells.y, r.grid.cells.z});
  j["grid"] = {{"origin", {r.grid.origin.x, r.grid.origin.y, r.grid.origin.z}},
               {"h", r.grid.h},
               {"cells", {r.grid.cells.x, r.grid.cells.y, r.grid.cells.z}}};
  j["volume"] = r.measure.volume;
  j["axis_volumes"] = {r.measure.axisVolume[0], r.measure.axisVolume[1], r.measure.axisVolume[2]};
  j["area"] = r.measure.area;
  if (std::isfinite(r.measure.thinnestWall)) {
    j["thinnest_wall"] = r.measure.thinnestWall;
    j["thinnest_wall_at"] = {r.measure.thinnestAt.x, r.measure.thinnestAt.y,
                             r.measure.thinnestAt.z};
  }
  j["surfels"] = r.measure.surfels;
  j["seconds"] = r.seconds;
  j["peak_bytes"] = r.peakBytes;
  j["cache_bytes"] = r.cacheBytes;
  j["computed"] = r.computed;
  j["reused"] = r.reused;
  auto& stages = j["stages"] = nlohmann::ordered_json::array();
  for (const StageStats& s : r.stages)
    stages.push_back({{"name", s.name},
                      {"seconds", s.seconds},
                      {"runs", s.runs},
                      {"surfels", s.surfels},
                      {"peak_bytes", s.peakBytes}});
  auto& nodes = j["nodes"] = nlohmann::ordered_json::array();
  for (const NodeRecord& n : r.nodes)
    nodes.push_back({{"id", n.id},
                     {"name", n.name},
                     {"kind", n.kind},
                     {"outcome", outcomeName(n.outcome)},
                     {"seconds", n.seconds},
                     {"surfels", n.surfels}});
  if (!c.output.empty()) j["output"] = {{"path", c.output}, {"points", c.outputPoints}};
  j["warnings"] = c.warnings;
  return j.dump(2) + "\n";
}

}  // namespace strata
