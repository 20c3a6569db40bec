// End-to-end tests of the `strata` command line: the same binary a user runs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "engine/io/mesh_formats.h"
#include "engine/io/scene_file.h"
#include "tests/support/export_cases.h"

namespace {

struct CliRun {
  int code = -1;
  std::string output;  // stdout and stderr together
};

// `usesGl`: the command loads a GL driver, whose own allocations LeakSanitizer would report
// (in the sanitizer build); leak checking is left to the tests of Strata's code alone.
CliRun strata(const std::string& args, bool withoutDisplay = false, bool usesGl = false) {
  std::string command = std::string(withoutDisplay ? "env -u DISPLAY -u WAYLAND_DISPLAY " : "") +
                        (usesGl ? "env ASAN_OPTIONS=detect_leaks=0 " : "") + STRATA_BINARY + " " +
                        args + " 2>&1";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) run.output.append(buffer, n);
  int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string temp(const std::string& name) {
  return testing::TempDir() + "/strata_cli_" + name;
}

std::string data(const std::string& name) {
  return std::string(STRATA_TEST_DATA) + "/" + name;
}

TEST(Cli, EvalPrintsReportAndWritesJson) {
  std::string report = temp("report.json");
  CliRun r = strata("eval " + std::string(STRATA_ASSETS) +
                    "/scenes/demo.strata.json --resolution 96 --report " + report + " -q");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("sample"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("volume"), std::string::npos);
  std::ifstream in(report);
  nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"volume", "area", "surfels", "peak_bytes", "stages", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GT(j["volume"].get<double>(), 0.0);
  bool sawSample = false;
  for (const auto& s : j["stages"]) {
    EXPECT_TRUE(s.contains("seconds"));
    if (s["name"] == "sample") sawSample = s["runs"].get<int>() > 0;
  }
  EXPECT_TRUE(sawSample);
}

TEST(Cli, BooleanOfMeshFilesWritesASurfelCloud) {
  std::string out = temp("union.ply");
  std::string report = temp("union.json");
  CliRun r = strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") +
                    " --resolution 64 --surfels " + out + " --report " + report + " -q");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream ply(out, std::ios::binary);
  std::string header;
  std::getline(ply, header);
  EXPECT_EQ(header, "ply");
  std::ifstream in(report);
  nlohmann::json j = nlohmann::json::parse(in);
  // A union with itself is the bunny: within a cell-sized tolerance of its exact volume.
  EXPECT_NEAR(j["volume"].get<double>(), 194.288371812, 0.05 * 194.288371812);
  EXPECT_GT(j["output"]["points"].get<int>(), 1000);
}

TEST(Cli, DifferenceOfAMeshWithItselfIsEmpty) {
  std::string report = temp("empty.json");
  CliRun r = strata("boolean difference " + data("eight.obj") + " " + data("eight.obj") +
                    " --resolution 64 --report " + report + " -q");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(report);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["surfels"].get<int>(), 0);
  EXPECT_EQ(j["volume"].get<double>(), 0.0);
}

TEST(Cli, BadInputsGiveClearErrors) {
  CliRun missing = strata("boolean union " + temp("nope.obj") + " " + data("bunny.obj"));
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.output.find("nope.obj"), std::string::npos) << missing.output;

  CliRun op = strata("boolean xor " + data("bunny.obj") + " " + data("bunny.obj"));
  EXPECT_EQ(op.code, 1);
  EXPECT_NE(op.output.find("unknown operation 'xor'"), std::string::npos) << op.output;

  CliRun option = strata("eval scene.strata.json --frobnicate");
  EXPECT_EQ(option.code, 1);
  EXPECT_NE(option.output.find("unknown option --frobnicate"), std::string::npos);

  CliRun resolution =
      strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") + " --resolution 3");
  EXPECT_EQ(resolution.code, 1);
  EXPECT_NE(resolution.output.find("--resolution"), std::string::npos) << resolution.output;

  CliRun unknownBackend =
      strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") + " --backend tpu");
  EXPECT_EQ(unknownBackend.code, 1);
  EXPECT_NE(unknownBackend.output.find("unknown backend 'tpu'"), std::string::npos)
      << unknownBackend.output;
  // --backend cuda where there is none (CI) says why and what to use; where there is a device
  // it succeeds.
  CliRun cuda = strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") +
                       " --resolution 32 -q --backend cuda");
  if (cuda.code != 0) {
    EXPECT_EQ(cuda.code, 1);
    EXPECT_NE(cuda.output.find("use --backend cpu"), std::string::npos) << cuda.output;
  }

  std::string notPly = temp("out.stl");
  CliRun format = strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") +
                         " --resolution 32 -q --surfels " + notPly);
  EXPECT_EQ(format.code, 1);
  EXPECT_NE(format.output.find("PLY"), std::string::npos) << format.output;
  EXPECT_FALSE(std::ifstream(notPly).good());

  std::string unknown = temp("out.xyz");
  CliRun exportFormat = strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") +
                               " --resolution 32 -q -o " + unknown);
  EXPECT_EQ(exportFormat.code, 1);
  EXPECT_NE(exportFormat.output.find("unknown export format 'xyz'"), std::string::npos)
      << exportFormat.output;
  EXPECT_FALSE(std::ifstream(unknown).good());
}

TEST(Cli, HelpAndNoArgumentsRunTheDemo) {
  CliRun help = strata("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("strata boolean"), std::string::npos);
  // Without a display, `strata` alone evaluates the demo on the command line (with one, it
  // would open the editor): hide any display this test runs under.
  CliRun demo = strata("", /*withoutDisplay=*/true);
  EXPECT_EQ(demo.code, 0) << demo.output;
  EXPECT_NE(demo.output.find("result"), std::string::npos);
}

// `--help` after any command prints the usage and runs nothing (no editor opens, no file is
// read), where the command's own parser would refuse an unknown option.
TEST(Cli, HelpAfterACommandPrintsTheUsage) {
  for (const std::string command : {"edit --help", "export --help", "boolean union -h",
                                    "eval missing.strata.json --help", "batch --help"}) {
    CliRun help = strata(command, /*withoutDisplay=*/true);
    EXPECT_EQ(help.code, 0) << command << "\n" << help.output;
    EXPECT_NE(help.output.find("strata boolean OP A B"), std::string::npos) << command;
    EXPECT_EQ(help.output.find("unknown option"), std::string::npos) << command;
  }
}

// The usage texts list the formats of engine/io/mesh_formats.h: --help every readable and
// writable extension, the export usage lines every writable one.
TEST(Cli, UsageListsEveryMeshFormat) {
  using strata::MeshAccess;
  CliRun help = strata("--help");
  ASSERT_EQ(help.code, 0);
  for (MeshAccess access : {MeshAccess::Read, MeshAccess::Write}) {
    for (const std::string& ext : strata::meshExtensions(access))
      EXPECT_NE(help.output.find("." + ext), std::string::npos) << ext << "\n" << help.output;
  }
  CliRun exportUsage = strata("export");
  CliRun booleanUsage = strata("boolean union");
  for (const std::string& ext : strata::meshExtensions(MeshAccess::Write)) {
    EXPECT_NE(exportUsage.output.find("." + ext), std::string::npos) << exportUsage.output;
    EXPECT_NE(booleanUsage.output.find("." + ext), std::string::npos) << booleanUsage.output;
  }
  // Upper-case extensions are accepted like lower-case ones.
  std::string upper = temp("UPPER.PLY");
  CliRun r = strata("boolean union " + data("bunny.obj") + " " + data("bunny.obj") +
                    " --resolution 32 -q -o " + upper);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::ifstream(upper).good());
}

// `strata render` needs no display: it renders through EGL (a window only where EGL is missing).
TEST(Cli, RenderWritesAPngWithoutADisplay) {
  const std::string png = temp("render.png");
  std::remove(png.c_str());
  CliRun r = strata("render " + std::string(STRATA_ASSETS) + "/scenes/demo.strata.json -o " + png +
                        " --resolution 64 --width 160 --height 100 --section x:0.4",
                    /*withoutDisplay=*/true, /*usesGl=*/true);
  if (r.output.find("has no editor") != std::string::npos) GTEST_SKIP() << r.output;
  if (r.output.find("headless OpenGL") != std::string::npos) GTEST_SKIP() << "no EGL: " << r.output;
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("rendering with EGL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("160 x 100"), std::string::npos) << r.output;
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST(Cli, RenderRejectsABadSection) {
  CliRun r = strata("render " + std::string(STRATA_ASSETS) + "/scenes/demo.strata.json -o " +
                    temp("bad.png") + " --section w:2");
  EXPECT_NE(r.code, 0);
  if (r.output.find("has no editor") != std::string::npos) GTEST_SKIP() << r.output;
  EXPECT_NE(r.output.find("--section: expected AXIS"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'w:2'"), std::string::npos) << r.output;
}

}  // namespace

namespace {

// `strata export` and `strata boolean ... -o`: a watertight mesh in each format, re-read and
// checked by the command itself; the JSON report carries the check.
TEST(CliExport, EveryFormatPassesTheCheck) {
  for (const std::string& ext : strata::meshExtensions(strata::MeshAccess::Write)) {
    std::string out = temp(std::string("export.") + ext);
    std::string report = temp(std::string("export_") + ext + ".json");
    CliRun r = strata("boolean difference " + data("bunny.obj") + " " + data("eight.obj") +
                      " --unit-scale 1 --resolution 64 -q -o " + out + " --report " + report);
    ASSERT_EQ(r.code, 0) << ext << ": " << r.output;
    EXPECT_NE(r.output.find("passed the watertight check"), std::string::npos) << r.output;
    std::ifstream in(report);
    nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_TRUE(j["check"]["passed"].get<bool>()) << ext;
    EXPECT_TRUE(j["check"]["closed"].get<bool>());
    EXPECT_EQ(j["check"]["components"].get<int>(), 1);
    EXPECT_NEAR(j["volume"].get<double>(), 194.288371812, 0.05 * 194.288371812) << ext;
  }
}

// Bodies the cells alone parted are said by the command line too (bodiesDifferSentence): bars
// joined at the estimate's probe and apart at the export's cells.
TEST(CliExport, BodiesTheCellsAloneJoinOrPartAreSaid) {
  const std::string scene = temp("close_bars.strata.json");
  strata::saveScene(strata::test::barsCloserThanTheProbesCell(600), scene);
  CliRun r =
      strata("export " + scene + " --resolution 600 --backend cpu -q -o " + temp("close_bars.stl"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("2 separate bodies at 600 cells, where the estimate's probe"),
            std::string::npos)
      << r.output;
}

// --simplify: fewer triangles, the same check passed, the deviation measured and reported.
TEST(CliExport, SimplifyKeepsTheCheckAndReportsTheDeviation) {
  const std::string out = temp("simplified.stl"), report = temp("simplified.json");
  CliRun r = strata("boolean difference " + data("bunny.obj") + " " + data("eight.obj") +
                    " --unit-scale 1 --resolution 96 -q --simplify 0.25 -o " + out + " --report " +
                    report);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("simplify "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("deviation (Hausdorff, both ways)"), std::string::npos) << r.output;
  std::ifstream in(report);
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["check"]["passed"].get<bool>());
  EXPECT_EQ(j["check"]["components"].get<int>(), 1);
  const auto& s = j["simplify"];
  EXPECT_TRUE(s["done"].get<bool>());
  EXPECT_LT(s["triangles_after"].get<double>(), 0.3 * s["triangles_before"].get<double>());
  EXPECT_EQ(s["triangles_after"].get<size_t>(), j["check"]["triangles"].get<size_t>());
  EXPECT_GT(s["samples"].get<size_t>(), 0u);
  // Within the bound asked for, proven by the measurement.
  EXPECT_LE(s["deviation_bound"].get<double>(), 0.25 * j["grid"]["h"].get<double>() * (1 + 1e-9));
  EXPECT_LE(s["measured_deviation"].get<double>(), s["deviation_bound"].get<double>());
  // A bad value is an error naming the option.
  r = strata("boolean union " + data("bunny.obj") + " " + data("eight.obj") +
             " -q --simplify none -o " + out);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find("--simplify"), std::string::npos) << r.output;
}

// strata offset / shell / round: the meshes' union under a modifier, with boolean's options.
TEST(CliExport, OffsetShellRoundAndFilletOfMeshFiles) {
  const std::string bunny = data("bunny.obj");
  const std::string out = temp("modified.stl");
  for (const std::string& command :
       {"offset " + bunny + " --distance 2", "offset " + bunny + " --distance -1",
        "shell " + bunny + " --thickness 1", "round " + bunny + " --radius 1",
        "round " + bunny + " " + data("eight.obj") + " --fillet 1"}) {
    CliRun r = strata(command + " --resolution 64 -q -o " + out);
    ASSERT_EQ(r.code, 0) << command << ": " << r.output;
    EXPECT_NE(r.output.find("passed the watertight check"), std::string::npos) << r.output;
  }
  CliRun missing = strata("shell " + bunny + " --resolution 32");
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.output.find("usage: strata shell A [B...] --thickness"), std::string::npos)
      << missing.output;
  CliRun both = strata("round " + bunny + " --radius 1 --fillet 1");
  EXPECT_EQ(both.code, 1);
  EXPECT_NE(both.output.find("--radius R"), std::string::npos) << both.output;
  CliRun zero = strata("shell " + bunny + " --thickness 0");
  EXPECT_EQ(zero.code, 1);
  EXPECT_NE(zero.output.find("must be greater than 0"), std::string::npos) << zero.output;
}

// The bundled scene of patterns: a mirrored pair of ribs, a circular array of 6 bolt holes, a
// 2 x 2 grid of mounting holes and a row of 3 slots. Exported whole and in tiles: one closed
// part whose genus counts every copy (bore 1 + 6 + 4 + 3), the same volume both ways.
TEST(CliExport, TheSceneOfPatternsExportsWatertightWithEveryCopy) {
  const std::string scene = std::string(STRATA_ASSETS) + "/scenes/flange_patterns.strata.json";
  double volumes[2] = {0.0, 0.0};
  for (int tiled = 0; tiled < 2; ++tiled) {
    const std::string report = temp("patterns.json");
    CliRun r = strata("export " + scene + " --resolution 128 -q -o " + temp("patterns.stl") +
                      " --report " + report + (tiled ? " --tile 32" : ""));
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(report);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["tiles"].get<int>() > 1, tiled == 1) << j["tiles"];
    const nlohmann::json& check = j["check"];
    EXPECT_TRUE(check["passed"].get<bool>()) << r.output;
    EXPECT_EQ(check["components"].get<int>(), 1) << r.output;
    EXPECT_EQ(check["genus"].get<int>(), 14) << r.output;
    volumes[tiled] = check["volume"].get<double>();
  }
  EXPECT_DOUBLE_EQ(volumes[0], volumes[1]);
}

// `shell A --thickness T --opening C`: A minus C, hollowed, the hollow open where C cuts: the
// outer and inner surfaces are one (one component, genus 0), where the closed shell of the
// same part has its cavity as a separate surface.
TEST(CliExport, ShellWithAnOpening) {
  const std::string bunny = data("bunny.obj");
  const std::string top = temp("bunny_top.obj");
  {
    // A box over the bunny's back (the file is y-up, 9.7 tall): y from 7 to 11.
    FILE* f = std::fopen(top.c_str(), "w");
    ASSERT_TRUE(f);
    std::fprintf(f,
                 "v -6 7 -5\nv 6 7 -5\nv -6 11 -5\nv 6 11 -5\nv -6 7 5\nv 6 7 5\nv -6 11 5\n"
                 "v 6 11 5\nf 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\n"
                 "f 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n");
    std::fclose(f);
  }
  const std::string out = temp("opened.stl");
  CliRun opened =
      strata("shell " + bunny + " --thickness 0.3 --opening " + top + " --resolution 96 -o " + out);
  ASSERT_EQ(opened.code, 0) << opened.output;
  EXPECT_NE(opened.output.find("passed the watertight check"), std::string::npos);
  EXPECT_NE(opened.output.find("components 1, genus 0"), std::string::npos) << opened.output;
  EXPECT_NE(opened.output.find("open where " + top + " cuts it"), std::string::npos)
      << opened.output;
  CliRun closed = strata("shell " + bunny + " --thickness 0.3 --resolution 96 -o " + out);
  ASSERT_EQ(closed.code, 0) << closed.output;
  EXPECT_EQ(closed.output.find("components 1,"), std::string::npos) << closed.output;
  CliRun wrong = strata("offset " + bunny + " --distance 1 --opening " + top);
  EXPECT_EQ(wrong.code, 1);
  EXPECT_NE(wrong.output.find("--opening applies to shell only"), std::string::npos)
      << wrong.output;
}

TEST(CliExport, SceneExportWithTilesAndErrors) {
  std::string out = temp("demo.stl");
  CliRun r = strata("export " + std::string(STRATA_ASSETS) +
                    "/scenes/demo.strata.json --resolution 96 --tile 32 -q -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("tiles"), std::string::npos) << r.output;
  CliRun missing = strata("export " + std::string(STRATA_ASSETS) + "/scenes/demo.strata.json");
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.output.find("usage: strata export"), std::string::npos);
  CliRun badDir = strata("export " + std::string(STRATA_ASSETS) +
                         "/scenes/demo.strata.json --resolution 32 -q -o /nonexistent/dir/x.stl");
  EXPECT_EQ(badDir.code, 1);
  EXPECT_NE(badDir.output.find("/nonexistent/dir/x.stl"), std::string::npos) << badDir.output;
}

TEST(CliExport, AJobThatCannotFitIsRefusedWithItsEstimate) {
  // The scaffold at 4096 cells: about 30 million triangles, some GiB; with 1 GiB allowed the
  // export is refused before any work, naming the job, the estimate and both ways on.
  const std::string scene = std::string(STRATA_ASSETS) + "/scenes/bone_scaffold.strata.json";
  const std::string out = temp("refused.stl");
  std::remove(out.c_str());
  CliRun r = strata("export " + scene + " --resolution 4096 --max-memory 1G -o " + out);
  EXPECT_EQ(r.code, 1) << r.output;
  for (const char* part :
       {"export of ", "bone_scaffold.strata.json at 4096 cells", "of memory",
        "1.0 GiB are available", "triangles", "tiles", "--resolution", "--force"})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << "\n" << r.output;
  FILE* written = std::fopen(out.c_str(), "rb");
  EXPECT_EQ(written, nullptr) << "nothing may be written";
  if (written) std::fclose(written);
  CliRun eval = strata("eval " + scene + " --resolution 4096 --max-memory 64M");
  EXPECT_EQ(eval.code, 1) << eval.output;
  EXPECT_NE(eval.output.find("evaluation of "), std::string::npos) << eval.output;
  CliRun badSize = strata("eval " + scene + " --max-memory lots");
  EXPECT_EQ(badSize.code, 1);
  EXPECT_NE(badSize.output.find("--max-memory: expected a size"), std::string::npos)
      << badSize.output;
  // A job that fits says nothing about estimates.
  CliRun small = strata("eval " + scene + " --resolution 128");
  EXPECT_EQ(small.code, 0) << small.output;
  EXPECT_EQ(small.output.find("estimate"), std::string::npos) << small.output;
}

// --stream: the same file written in pieces; what it cannot write, refused by name.
TEST(CliExport, AStreamedExportWritesTheSameFile) {
  const std::string whole = temp("whole.stl"), streamed = temp("streamed.stl");
  const std::string job = "boolean difference " + data("bunny.obj") + " " + data("eight.obj") +
                          " --unit-scale 1 --resolution 96 -q --tile 16 -o ";
  CliRun a = strata(job + whole);
  ASSERT_EQ(a.code, 0) << a.output;
  CliRun b = strata(job + streamed + " --stream");
  ASSERT_EQ(b.code, 0) << b.output;
  EXPECT_NE(b.output.find("passed the watertight check"), std::string::npos) << b.output;
  std::ifstream x(whole, std::ios::binary), y(streamed, std::ios::binary);
  std::stringstream bx, by;
  bx << x.rdbuf();
  by << y.rdbuf();
  EXPECT_GT(bx.str().size(), 84u);
  EXPECT_EQ(bx.str(), by.str());
  // PLY: its vertices listed before the faces, the same file as in memory.
  CliRun wholePly = strata(job + temp("whole.ply"));
  ASSERT_EQ(wholePly.code, 0) << wholePly.output;
  CliRun ply = strata(job + temp("streamed.ply") + " --stream");
  ASSERT_EQ(ply.code, 0) << ply.output;
  EXPECT_NE(ply.output.find("passed the watertight check"), std::string::npos) << ply.output;
  std::ifstream px(temp("whole.ply"), std::ios::binary), py(temp("streamed.ply"), std::ios::binary);
  std::stringstream bpx, bpy;
  bpx << px.rdbuf();
  bpy << py.rdbuf();
  EXPECT_GT(bpx.str().size(), 300u);
  EXPECT_TRUE(bpx.str() == bpy.str()) << "the streamed PLY differs";
  CliRun obj = strata(job + temp("streamed.obj") + " --stream");
  EXPECT_EQ(obj.code, 1);
  EXPECT_NE(obj.output.find("--stream writes binary STL (.stl) or PLY (.ply) only"),
            std::string::npos)
      << obj.output;
  // --gpus goes with --stream (exportSceneStreamed on workers); without CUDA it says why.
  CliRun gpus = strata(job + streamed + " --stream --gpus 2 --backend cpu");
  EXPECT_EQ(gpus.code, 1);
  EXPECT_NE(gpus.output.find("--gpus: exports on several GPUs need the CUDA backend"),
            std::string::npos)
      << gpus.output;
}

// A report or the surfels written over the input, the output or each other would lose one of
// them (a hostile-input test replaced its scene with the report): refused before any work. The
// output may still replace its input (it is read first).
TEST(Cli, SideFilesNeverReplaceTheInputOrTheOutput) {
  const std::string scene = temp("side_files.strata.json");
  {
    std::ifstream in(std::string(STRATA_ASSETS) + "/scenes/two_spheres.strata.json");
    std::ofstream out(scene);
    out << in.rdbuf();
  }
  const std::string out = temp("side_files.stl");
  CliRun overScene = strata("eval " + scene + " --resolution 32 --report " + scene);
  EXPECT_EQ(overScene.code, 1) << overScene.output;
  EXPECT_NE(overScene.output.find("the same file as the input"), std::string::npos)
      << overScene.output;
  std::string sameOut = out;  // another spelling of the same path
  sameOut.insert(sameOut.rfind('/') + 1, "./");
  CliRun overOutput =
      strata("export " + scene + " --resolution 32 -q -o " + out + " --report " + sameOut);
  EXPECT_EQ(overOutput.code, 1) << overOutput.output;
  EXPECT_NE(overOutput.output.find("the same file as -o"), std::string::npos) << overOutput.output;
  std::ifstream kept(scene);
  std::string first;
  std::getline(kept, first);
  EXPECT_EQ(first, "{") << "the scene is still the scene";
  const std::string device = temp("side_files_null.stl");
  std::remove(device.c_str());
  ASSERT_EQ(::symlink("/dev/null", device.c_str()), 0);
  CliRun toDevice = strata("export " + scene + " --resolution 32 -q -o " + device);
  EXPECT_EQ(toDevice.code, 1) << toDevice.output;
  EXPECT_NE(toDevice.output.find("not a regular file"), std::string::npos) << toDevice.output;
  std::remove(device.c_str());
}

// An output that is the user's link (part.stl -> prints/part-v2.stl) stays a link: the export
// replaces the file it leads to and checks that file.
TEST(Cli, AnOutputThatIsALinkKeepsItAndWritesTheFileItLeadsTo) {
  const std::string scene = std::string(STRATA_ASSETS) + "/scenes/two_spheres.strata.json";
  const std::string real = temp("linked_output_real.stl");
  const std::string link = temp("linked_output.stl");
  std::remove(real.c_str());
  std::remove(link.c_str());
  std::ofstream(real) << "an older export";
  ASSERT_EQ(::symlink(real.c_str(), link.c_str()), 0);
  CliRun run = strata("export " + scene + " --resolution 32 -q -o " + link);
  EXPECT_EQ(run.code, 0) << run.output;
  struct stat st;
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode)) << "the link was replaced by a file";
  std::ifstream written(real, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(written)), {});
  EXPECT_GT(bytes.size(), 84u) << "the file the link leads to was not written";
  std::remove(link.c_str());
  std::remove(real.c_str());
}

// An export whose result is empty names the scene and says why (a numbers check met
// "out.stl: nothing to write (the mesh has no triangles)": the output, not the input, and no
// cause), in memory and streamed.
TEST(Cli, AnEmptyResultNamesTheSceneAndSaysWhy) {
  const std::string scene = temp("empty_result.strata.json");
  std::ofstream(scene) << "{\"format\": \"strata-scene\", \"version\": 4, \"root\": {\"id\": 1, "
                          "\"type\": \"offset\", \"distance\": -1.01, \"children\": [{\"id\": 2, "
                          "\"type\": \"box\", \"size\": [2, 3, 4]}]}}";
  const std::string out = temp("empty_result.stl");
  std::remove(out.c_str());
  for (const std::string extra : {"", " --stream"}) {
    CliRun r = strata("export " + scene + " --resolution 32 --backend cpu -q -o " + out + extra);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(scene + ": the result is empty, so nothing was written to " + out),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("left nothing"), std::string::npos) << r.output;
    EXPECT_FALSE(std::ifstream(out).good()) << extra;
  }
}

// A scene that no grid can measure (a box of 1e308) is refused before any work, naming the file.
TEST(Cli, ASceneTooLargeToMeasureIsRefusedNamingTheFile) {
  const std::string scene = temp("huge_box.strata.json");
  std::ofstream(scene) << "{\"format\": \"strata-scene\", \"version\": 1, \"root\": {\"id\": 1, "
                          "\"type\": \"box\", \"size\": [1e308, 1e308, 1e308]}}";
  CliRun r = strata("eval " + scene + " --resolution 32");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(scene + ": the scene spans 1e+308 units"), std::string::npos) << r.output;
}

// An error found past reading (here the leaf limit, met when the scene is expanded) names what
// the command reads, for eval and export alike.
TEST(Cli, AnErrorPastReadingNamesTheInput) {
  for (const std::string& out : {std::string(), " -o " + temp("limit.stl")}) {
    CliRun r = strata("boolean union " + data("bunny.obj") + " " + data("eight.obj") +
                      " --resolution 32 --max-leaves 1" + out);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("error: union of " + data("bunny.obj") + " " + data("eight.obj") +
                            ": the scene expands to 2 visible leaves"),
              std::string::npos)
        << r.output;
  }
}

// An empty scene name (a script's empty variable) is refused, not opened as a new scene.
TEST(Cli, AnEmptySceneNameIsRefused) {
  CliRun r = strata("edit ''", /*withoutDisplay=*/true);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("the scene's file name is empty"), std::string::npos) << r.output;
}

// Warnings past the first 20 are counted, not printed (a scene of 2,000 copies printed 2,001
// lines of one warning); the report's JSON keeps them all.
TEST(Cli, ManyWarningsAreCountedPastTheFirstTwenty) {
  const std::string scene = temp("specks.strata.json"), report = temp("specks.json");
  std::string children;
  for (int i = 0; i < 30; ++i)
    children += "{\"id\": " + std::to_string(i + 2) + ", \"type\": \"box\", \"name\": \"speck " +
                std::to_string(i) +
                "\", \"size\": [1e-4, 1e-4, 1e-4], \"transform\": " + "{\"translate\": [" +
                std::to_string(i) + ", 0, 0]}}, ";
  std::ofstream(scene) << "{\"format\": \"strata-scene\", \"version\": 1, \"root\": {\"id\": 1, "
                          "\"type\": \"union\", \"children\": ["
                       << children << "{\"id\": 100, \"type\": \"box\", \"size\": [40, 5, 5]}]}}";
  CliRun r = strata("eval " + scene + " --resolution 32 --report " + report);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("and 10 more"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("more warnings follow"), std::string::npos) << r.output;
  size_t printed = 0;  // on stderr and in the summary, 20 each
  for (size_t at = r.output.find("smaller than a cell"); at != std::string::npos;
       at = r.output.find("smaller than a cell", at + 1))
    ++printed;
  EXPECT_EQ(printed, 40u) << r.output;
  std::ifstream in(report);
  EXPECT_EQ(nlohmann::json::parse(in)["warnings"].size(), 30u);
}

// The tiles a streamed export's estimate names are the ones it then runs (its slabs, not the
// in-memory export's cubes: one tile here, eight slabs).
TEST(CliExport, AStreamedEstimateNamesTheTilesItRuns) {
  const std::string scene = std::string(STRATA_ASSETS) + "/scenes/two_spheres.strata.json";
  const std::string out = temp("estimated_streamed.stl"), report = temp("estimated.json");
  const std::string job = "export " + scene + " --resolution 600 --backend cpu --stream -o " + out;
  CliRun refused = strata(job + " --max-memory 1M");
  EXPECT_EQ(refused.code, 1) << refused.output;
  const size_t at = refused.output.find(" tiles, about");
  ASSERT_NE(at, std::string::npos) << refused.output;
  const size_t from = refused.output.rfind(", ", at) + 2;
  const int estimated = std::stoi(refused.output.substr(from, at - from));
  CliRun ran = strata(job + " -q --report " + report);
  ASSERT_EQ(ran.code, 0) << ran.output;
  std::ifstream in(report);
  const int tiles = nlohmann::json::parse(in)["tiles"].get<int>();
  EXPECT_GT(tiles, 1);
  EXPECT_EQ(estimated, tiles) << refused.output;
}

// A job whose mesh would not fit, but whose pieces would, names --stream.
TEST(CliExport, ARefusedExportNamesTheStreamedOneWhereItWouldFit) {
  const std::string scene = std::string(STRATA_ASSETS) + "/scenes/bone_scaffold.strata.json";
  const std::string out = temp("refused_streamed.stl");
  // Its estimate (12 GiB whole, 8 GiB in pieces: most of it the offsets' windows) against
  // 10 GiB allowed, and against 2 GiB, where --stream would not fit either.
  CliRun r = strata("export " + scene + " --resolution 4096 --max-memory 10G -o " + out);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("write it in pieces with --stream"), std::string::npos) << r.output;
  CliRun tight = strata("export " + scene + " --resolution 4096 --max-memory 2G -o " + out);
  EXPECT_EQ(tight.code, 1) << tight.output;
  EXPECT_EQ(tight.output.find("--stream"), std::string::npos) << tight.output;
}

TEST(Cli, AScreenshotWithoutADisplayIsAnError) {
  const std::string out = temp("nodisplay.png");
  std::remove(out.c_str());
  CliRun r =
      strata("edit " + std::string(STRATA_ASSETS) + "/scenes/demo.strata.json --screenshot " + out,
             /*withoutDisplay=*/true);
  if (r.output.find("this build has no editor") != std::string::npos)
    GTEST_SKIP() << "built without the editor";
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("--screenshot needs a window"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("strata render"), std::string::npos) << r.output;
  FILE* f = std::fopen(out.c_str(), "rb");
  EXPECT_EQ(f, nullptr);
  if (f) std::fclose(f);
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// `strata batch FILE`: each line a command as typed after `strata`, run in one process (the
// CUDA driver's start, 0.3 s a process on an H200, paid once). Each job writes what the same
// command alone writes; quotes, comments and a leading "strata" read as a shell reads them.
TEST(CliBatch, EachLineRunsAsTheCommandAloneWould) {
  const std::string folder = temp("batch dir");
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string alone = folder + "/alone.stl", jobs = folder + "/jobs.txt";
  ASSERT_EQ(strata("boolean difference " + data("bunny.obj") + " " + data("eight.obj") +
                   " --resolution 48 -q -o '" + alone + "'")
                .code,
            0);
  {
    std::ofstream out(jobs);
    out << "# two jobs and a comment\n\n"
        << "strata boolean difference " << data("bunny.obj") << " '" << data("eight.obj")
        << "' --resolution 48 -q -o \"" << folder << "/in batch.stl\"  # the same command\n"
        << "eval " << STRATA_ASSETS << "/scenes/demo.strata.json --resolution 32 -q\n";
  }
  CliRun r = strata("batch '" + jobs + "'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("job 2 of 2 (line 4): eval"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 jobs in"), std::string::npos) << r.output;
  EXPECT_EQ(fileBytes(folder + "/in batch.stl"), fileBytes(alone));
  EXPECT_FALSE(fileBytes(alone).empty());
  std::filesystem::remove_all(folder);
}

// Every line is checked before the first job runs (a typo on line 3 left nothing half done);
// a failing job stops the batch unless -k; the exit code is the first failure's.
TEST(CliBatch, BadLinesStopItBeforeAnyJobAndAFailureStopsItUnlessKeepGoing) {
  const std::string folder = temp("batch_bad");
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string made = folder + "/made.stl", jobs = folder + "/jobs.txt";
  const std::string good = "boolean union " + data("bunny.obj") + " " + data("eight.obj") +
                           " --resolution 32 -q -o " + made + "\n";
  std::ofstream(jobs) << good << "eval a.strata.json\nboolean union \"x.obj y.obj\n";
  CliRun r = strata("batch " + jobs);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find(jobs + ":3: a double quote (\") is not closed"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(made)) << "no job ran";
  std::ofstream(jobs) << "edit demo.strata.json\n";
  r = strata("batch " + jobs);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.output.find(jobs + ":1: 'edit' cannot run in a batch"), std::string::npos)
      << r.output;
  std::ofstream(jobs) << "eval " << folder << "/missing.strata.json -q\n" << good;
  r = strata("batch " + jobs);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("missing.strata.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("failed: line 1; the 1 after it not run"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(made));
  r = strata("batch -k " + jobs);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("2 of 2 jobs run"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(made)) << "the job after the failure ran";
  // A FIFO given as the file is refused, not waited on (it hung the batch).
  const std::string fifo = folder + "/jobs.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  r = strata("batch " + fifo);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("is a FIFO"), std::string::npos) << r.output;
  std::filesystem::remove_all(folder);
}

}  // namespace
