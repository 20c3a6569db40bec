// strata: the command line and the editor on the engine's code path.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/editor_commands.h"
#include "app/huge_pages.h"
#include "app/signal_cancellation.h"
#include "engine/io/mesh_formats.h"

namespace {

// The usage text around the lists of mesh formats (mesh_formats.h), which usage() fills in.
const char* kUsageHead =
    "strata: CSG Booleans of closed triangle meshes through layered depth images\n"
    "\n"
    "usage:\n"
    "  strata                         open the editor on the bundled demo scene (without a\n"
    "                                 display: evaluate it and print the report)\n"
    "  strata SCENE.strata.json       open a scene in the editor (also: strata edit [SCENE])\n"
    "  strata eval SCENE.strata.json  evaluate a scene file\n"
    "  strata boolean OP A B [C...]   apply union|intersection|difference to mesh files\n"
    "                                 (difference: A minus all the others)\n"
    "  strata offset A [B...] --distance D\n"
    "                                 the meshes' union grown (D > 0) or shrunk (D < 0) by D\n"
    "  strata shell A [B...] --thickness T [--opening C]\n"
    "                                 a wall of thickness T inside the union's surface; with\n"
    "                                 --opening, the union minus C, its wall open where C cuts\n"
    "  strata round A [B...] --radius R | --fillet R\n"
    "                                 convex edges rounded (--radius) or concave edges and\n"
    "                                 seams filled (--fillet) with radius R; these three take\n"
    "                                 boolean's options\n"
    "  strata export SCENE -o FILE    write the scene's result as a watertight mesh\n"
    "  strata render SCENE -o F.png   render the editor's view of the scene to a PNG\n"
    "                                 (--width W --height H, --view iso|front|right|top...)\n"
    "  strata batch FILE [-k]         run the commands of FILE (one a line, as typed after\n"
    "                                 strata; - reads standard input) in one process, the\n"
    "                                 backend started once; stops at the first failure unless\n"
    "                                 -k (--keep-going)\n"
    "\n"
    "options:\n"
    "  --resolution N    cells along the longest side (default: the scene's, 256 for boolean)\n"
    "  --report FILE     write the report as JSON\n";
const char* kUsageOptions =
    "  --tile N          export: tile edge in cells, at most 1024 (default: the fewest tiles\n"
    "                    whose arrays take a quarter of the backend's free memory)\n"
    "  --simplify E      export, boolean -o: fewer triangles by edge collapses, the surface\n"
    "                    kept within E cells of the unsimplified one (e.g. 0.25), topology,\n"
    "                    orientation and sharp edges kept; the deviation is measured\n"
    "  --gpus N|all      export, boolean -o: tiles spread over N workers on the CUDA devices\n"
    "                    (default all: one a device; more than the devices share them)\n"
    "  --stream          export, boolean -o to .stl or .ply: written in pieces (a slab of tiles at "
    "a\n"
    "                    time, through a scratch file beside the output), never holding the\n"
    "                    mesh: for meshes larger than memory; the same bytes (--gpus too)\n"
    "  --distributed     export, boolean -o under mpirun: the tiles shared among the MPI\n"
    "                    processes, process 0 writes the file (the same bytes as one process)\n"
    "  --surfels F.ply   eval, boolean: write the result's surfels as a point cloud\n"
    "  --backend B       auto | cpu | cuda (default auto)\n"
    "  --threads N       worker threads (default: all cores, or STRATA_THREADS)\n"
    "  --max-file-size S read input files up to S bytes (K, M, G, T; default 4G); larger\n"
    "                    files, FIFOs and devices are refused before reading\n"
    "  --max-triangles N read meshes of up to N triangles (default 100000000, 3MF\n"
    "                    components included); larger ones are refused before they are\n"
    "                    prepared\n"
    "  --max-leaves N    evaluate scenes whose instances expand to more than 100000\n"
    "                    visible leaves (refused by default, before any work)\n"
    "  --nodes           list every node: computed or reused, time, surfels\n"
    "  --allow-open      try open or non-manifold meshes instead of rejecting them\n"
    "  --max-memory S    refuse jobs estimated to need more than S bytes of memory (K, M,\n"
    "                    G, T; default: what the system has available)\n"
    "  --force           run a job whose estimate (printed before a long job, from a\n"
    "                    64-cell probe) needs more memory or disk than is free\n"
    "  --unit-scale S    boolean: multiply mesh coordinates by S\n"
    "  --margin M        boolean: grid margin as a fraction of the bounds (default 0.05)\n"
    "  -q, --quiet       no progress bar or backend line\n"
    "\n"
    "Editor and render options:\n"
    "  --width W --height H       window or image size in pixels (the editor's default\n"
    "                             1600 x 1000, shrunk to fit the screen)\n"
    "  --view V                   render: iso, front, back, right, left, top, bottom\n"
    "  --ortho                    render: orthographic\n"
    "  --section AXIS[:AT][:flip] cut across x, y or z at the fraction AT of the bounds, capped\n"
    "  --screenshot F.png         edit: write the whole window once the preview settled, exit\n"
    "  --no-interop               edit: splats through the host instead of CUDA-GL interop\n"
    "  --no-pinning               edit: the host path's splat buffers left pageable\n"
    "  --select \"A[,B...]\"        edit: select the nodes with these names (with --screenshot)\n"
    "  --ghosts                   edit: show the ghosts of every part that cuts or intersects\n"
    "  --splats auto|points|quads|compute  how the view draws splats (auto: the kind the GPU\n"
    "                             draws fastest)\n"
    "  --measure-latency N --move-leaf NAME   edit: edit-to-screen time of N moves of a leaf\n"
    "  --drag                     with --measure-latency: the N moves as one drag (drafts)\n"
    "  --edit-wait MS             edit: how long a frame that sent an edit waits for its result\n"
    "                             before drawing the view (default 8; 0: the result is drawn by\n"
    "                             the frame after its arrival)\n"
    "  --measure-frames S         edit: UI time per frame while the engine evaluates, S seconds\n"
    "\n";
const char* kUsageTail =
    "Ctrl-C (SIGINT), SIGTERM and SIGHUP cancel cleanly: nothing half-written is left\n"
    "behind, and the exit code is 128 + the signal's number (130, 143, 129).\n";

// `text` broken at spaces into lines of at most kUsageWidth characters, the first starting with
// `first`, the others indented to its width.
std::string wrapped(const std::string& first, const std::string& text) {
  constexpr size_t kUsageWidth = 90;
  std::string out = first, line;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find(' ', begin);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(begin, end - begin);
    begin = end + 1;
    if (!line.empty() && first.size() + line.size() + 1 + word.size() > kUsageWidth) {
      out += line + "\n" + std::string(first.size(), ' ');
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line + "\n";
}

std::string usage() {
  using strata::MeshAccess;
  return kUsageHead +
         wrapped("  -o FILE           ",
                 "export (export, boolean): a closed, oriented, manifold mesh as " +
                     strata::meshFormatUsage(MeshAccess::Write) +
                     "; written atomically, then re-read and checked") +
         kUsageOptions + wrapped("Mesh files: ", strata::meshFormatUsage(MeshAccess::Read)) +
         kUsageTail;
}

int runCommand(const std::vector<std::string>& args) {
  if (args.empty()) return strata::runEdit({});
  const std::string command = args[0];
  std::vector<std::string> rest(args.begin() + 1, args.end());
  // `strata --help`, and `strata COMMAND ... --help` for every command (its own option parser
  // would refuse the flag): the usage, exit 0, nothing run.
  const auto isHelp = [](const std::string& a) { return a == "--help" || a == "-h"; };
  if (isHelp(command) || command == "help" || std::any_of(rest.begin(), rest.end(), isHelp)) {
    std::fputs(usage().c_str(), stdout);
    return 0;
  }
  if (command == "--version") {
    std::puts("strata 0.1.0");
    return 0;
  }
  if (command == "eval") return strata::runEval(rest);
  if (command == "boolean") return strata::runBoolean(rest);
  if (command == "export") return strata::runExport(rest);
  if (command == "offset" || command == "shell" || command == "round")
    return strata::runModifier(command, rest);
  if (command == "edit") return strata::runEdit(rest);
  if (command == "render") return strata::runRender(rest);
  if (command == "batch") return strata::runBatch(rest, runCommand);
  if (strata::looksLikeScenePath(command)) return strata::runEdit(args);
  std::fprintf(stderr, "strata: unknown command '%s'\n\n%s", command.c_str(), usage().c_str());
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  strata::restartWithHugePageMalloc(argv);  // first: it may re-execute the process
  // For the whole command, loading included (app/signal_cancellation.h).
  strata::SignalCancellation signals;
  return strata::exitCodeAfterSignals(runCommand(std::vector<std::string>(argv + 1, argv + argc)));
}
