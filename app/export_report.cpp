#include "app/export_report.h"

#include "app/cli_common.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>
#include <string>

#include "engine/export/drop_specks.h"

namespace strata {
namespace {
const char* yes(bool b) {
  return b ? "yes" : "NO";
}
std::string mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / 1048576.0);
  return text;
}
}  // namespace

std::string formatExportText(const ExportSummary& summary) {
  ExportSummary s = summary;
  s.unit = unitAbbreviation(s.unit);
  std::ostringstream out;
  char line[512];
  const ContourReport& r = s.result.contour;
  out << "input     " << s.input << "\n";
  out << "backend   " << s.backend << "\n";
  std::snprintf(line, sizeof(line), "grid      %d x %d x %d cells, h = %.6g %s, %d tile%s\n",
                r.grid.cells.x, r.grid.cells.y, r.grid.cells.z, r.grid.h, s.unit.c_str(), r.tiles,
                r.tiles == 1 ? "" : "s");
  out << line;
  std::snprintf(line, sizeof(line),
                "time      evaluate %.3f s, contour %.3f s, merge %.3f s, write %.3f s, check "
                "%.3f s; peak memory %s\n",
                r.evaluateSeconds, r.contourSeconds, r.mergeSeconds, s.result.writeSeconds,
                s.result.checkSeconds, mib(r.peakBytes).c_str());
  out << line;
  if (!s.distributed.empty()) out << "processes " << s.distributed << "\n";
  const SimplifyReport& sr = s.result.simplify;
  if (sr.refused) {
    out << "simplify  not done: " << sr.refusedWhy << "\n";
  } else if (sr.trianglesBefore) {
    std::snprintf(
        line, sizeof(line),
        "simplify  %zu -> %zu triangles (%.1f%%) in %.3f s (measuring %.3f s); "
        "rules' tolerance %.3g h%s\n",
        sr.trianglesBefore, sr.trianglesAfter,
        100.0 * double(sr.trianglesAfter) / double(sr.trianglesBefore), sr.seconds,
        sr.measureSeconds, r.grid.h > 0 ? sr.rulesTolerance / r.grid.h : 0.0,
        sr.attempts > 1 ? (" (attempt " + std::to_string(sr.attempts) + ")").c_str() : "");
    out << line;
    const SurfaceDeviation& d = sr.measured;
    std::snprintf(line, sizeof(line),
                  "          deviation (Hausdorff, both ways) %.3g h, proven at most %.3g h of "
                  "the %.3g h asked (unsimplified -> simplified %.3g h, back %.3g h; %zu "
                  "points%s)\n",
                  d.largest() / r.grid.h, d.bound() / r.grid.h, sr.tolerance / r.grid.h,
                  d.aToB / r.grid.h, d.bToA / r.grid.h, d.samples,
                  d.capped ? "; some beyond the search radius" : "");
    out << line;
  }
  out << "wrote     " << s.output << "\n";
  const MeshCheck& c = s.result.check;
  std::snprintf(line, sizeof(line),
                "check     %zu triangles, %zu vertices: closed %s, manifold %s, oriented %s, "
                "components %d, genus %d\n",
                c.triangles, c.vertices, yes(c.closed()), yes(c.manifold()), yes(c.oriented()),
                c.components, c.genus);
  out << line;
  std::snprintf(line, sizeof(line),
                "          volume %.9g %s^3, area %.9g %s^2, smallest triangle %.3g %s^2, "
                "degenerate %zu\n",
                c.volume, s.unit.c_str(), c.area, s.unit.c_str(), c.smallestTriangleArea,
                s.unit.c_str(), c.degenerateTriangles);
  out << line;
  std::snprintf(line, sizeof(line),
                "          deviation bound %.6g %s (sqrt(3) h: every vertex lies in a cell the "
                "surface crosses); fitted-plane distance max %.3g %s\n",
                r.deviationBound, s.unit.c_str(), r.maxPlaneDistance, s.unit.c_str());
  out << line;
  if (r.synthesizedCrossings || r.signDisagreements) {
    std::snprintf(line, sizeof(line),
                  "          %llu node signs decided by majority, %llu crossings synthesised "
                  "(tangent rays)\n",
                  static_cast<unsigned long long>(r.signDisagreements),
                  static_cast<unsigned long long>(r.synthesizedCrossings));
    out << line;
  }
  if (r.unfoldedShells) {
    std::snprintf(line, sizeof(line),
                  "          %d shell%s folded inside out by vertex placement (parts thinner than "
                  "a cell) pulled back towards the cell centres\n",
                  r.unfoldedShells, r.unfoldedShells == 1 ? "" : "s");
    out << line;
  }
  if (r.droppedSpecks.components)
    out << "          " << droppedSpecksSentence(r.droppedSpecks) << "\n";
  const DegenerateRepair& dr = s.result.degenerateRepair;
  if (dr.flipped || dr.rotated || dr.collapsed) {
    std::snprintf(line, sizeof(line),
                  "          %zu triangle%s without area as the file stores them repaired (%zu "
                  "edges flipped, %zu turned, %zu zero-length edges collapsed)\n",
                  dr.flipped + dr.rotated + dr.collapsed,
                  dr.flipped + dr.rotated + dr.collapsed == 1 ? "" : "s", dr.flipped, dr.rotated,
                  dr.collapsed);
    out << line;
  }
  if (!s.result.fileDifference.empty())
    out << "          the file differs from the mesh written: " << s.result.fileDifference << "\n";
  out << "result    " << (s.result.passed() ? "passed" : "FAILED") << " the watertight check\n";
  out << warningLines(s.warnings);
  return out.str();
}

std::string formatExportJson(const ExportSummary& s) {
  const ContourReport& r = s.result.contour;
  const MeshCheck& c = s.result.check;
  nlohmann::ordered_json j;
  j["input"] = s.input;
  j["output"] = s.output;
  j["unit"] = s.unit;
  j["backend"] = s.backend;
  j["grid"] = {{"origin", {r.grid.origin.x, r.grid.origin.y, r.grid.origin.z}},
               {"h", r.grid.h},
               {"cells", {r.grid.cells.x, r.grid.cells.y, r.grid.cells.z}}};
  j["tiles"] = r.tiles;
  if (!s.distributed.empty())
    j["distributed"] = {{"processes", s.processes},
                        {"description", s.distributed},
                        {"tiles_seconds", s.distributedTilesSeconds}};
  j["stages"] =
      nlohmann::ordered_json::array({{{"name", "evaluate"}, {"seconds", r.evaluateSeconds}},
                                     {{"name", "contour"}, {"seconds", r.contourSeconds}},
                                     {{"name", "merge"}, {"seconds", r.mergeSeconds}},
                                     {{"name", "write"}, {"seconds", s.result.writeSeconds}},
                                     {{"name", "check"}, {"seconds", s.result.checkSeconds}}});
  if (!r.mergeSteps.empty()) {
    nlohmann::ordered_json steps = nlohmann::ordered_json::array();
    for (const auto& [name, seconds] : r.mergeSteps)
      steps.push_back({{"name", name}, {"seconds", seconds}});
    j["merge_steps"] = steps;
  }
  j["peak_bytes"] = r.peakBytes;
  j["surfels"] = r.surfels;
  if (s.result.simplify.trianglesBefore || s.result.simplify.refused) {
    const SimplifyReport& sr = s.result.simplify;
    j["simplify"] = {{"done", !sr.refused},
                     {"why_not", sr.refusedWhy},
                     {"triangles_before", sr.trianglesBefore},
                     {"triangles_after", sr.trianglesAfter},
                     {"tolerance", sr.tolerance},
                     {"seconds", sr.seconds},
                     {"measure_seconds", sr.measureSeconds},
                     {"attempts", sr.attempts},
                     {"rules_tolerance", sr.rulesTolerance},
                     {"first_attempt_bound", sr.firstAttemptBound},
                     {"measured_deviation", sr.measured.largest()},
                     {"measured_to_simplified", sr.measured.aToB},
                     {"measured_to_unsimplified", sr.measured.bToA},
                     {"deviation_bound", sr.measured.bound()},
                     {"bound_to_simplified", sr.measured.aToBBound},
                     {"bound_to_unsimplified", sr.measured.bToABound},
                     {"accuracy", sr.measured.accuracy},
                     {"samples", sr.measured.samples}};
  }
  j["dropped_specks"] = {{"components", r.droppedSpecks.components},
                         {"triangles", r.droppedSpecks.triangles}};
  j["check"] = {{"passed", s.result.passed()},
                {"triangles", c.triangles},
                {"vertices", c.vertices},
                {"closed", c.closed()},
                {"manifold", c.manifold()},
                {"oriented", c.oriented()},
                {"components", c.components},
                {"genus", c.genus},
                {"volume", c.volume},
                {"area", c.area},
                {"smallest_triangle_area", c.smallestTriangleArea},
                {"degenerate_triangles", c.degenerateTriangles},
                {"file_matches", s.result.fileDifference.empty()}};
  if (!s.result.fileDifference.empty()) j["check"]["file_difference"] = s.result.fileDifference;
  j["volume"] = c.volume;
  j["area"] = c.area;
  j["deviation_bound"] = r.deviationBound;
  j["max_plane_distance"] = r.maxPlaneDistance;
  j["synthesized_crossings"] = r.synthesizedCrossings;
  j["sign_disagreements"] = r.signDisagreements;
  j["unfolded_shells"] = r.unfoldedShells;
  j["degenerate_repair"] = {{"flipped", s.result.degenerateRepair.flipped},
                            {"rotated", s.result.degenerateRepair.rotated},
                            {"collapsed", s.result.degenerateRepair.collapsed},
                            {"left", s.result.degenerateRepair.left}};
  j["warnings"] = s.warnings;
  return j.dump(2) + "\n";
}

}  // namespace strata
