#include "app/process_group_plugin.h"

#include <dlfcn.h>
#include <unistd.h>

#include <string>

#include "engine/util/error.h"

namespace strata {
namespace {

using OpenGroup = ProcessGroup* (*)(int*, char***, char*, size_t);

std::string folderOfThisBinary() {
  char path[4096];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof(path) - 1);
  if (n <= 0) return ".";
  const std::string p(path, size_t(n));
  const size_t slash = p.rfind('/');
  return slash == std::string::npos ? "." : p.substr(0, slash);
}

}  // namespace

std::unique_ptr<ProcessGroup> openMpiProcessGroup() {
  const std::string plugin = folderOfThisBinary() + "/libstrata_mpi.so";
  if (access(plugin.c_str(), F_OK) != 0)
    throw Error("--distributed: this strata was built without MPI (" + plugin +
                " is missing); install libopenmpi-dev and openmpi-bin (.ci/deps does) and build "
                "again");
  // Global: Open MPI's own components, loaded later, resolve their symbols against libmpi.
  void* handle = dlopen(plugin.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (!handle)
    throw Error("--distributed: cannot load " + plugin + ": " + dlerror() +
                " (is Open MPI installed? Debian: openmpi-bin)");
  auto open = reinterpret_cast<OpenGroup>(dlsym(handle, "strataOpenMpiProcessGroup"));
  if (!open) throw Error("--distributed: " + plugin + " is not Strata's MPI plugin");
  char error[512] = "";
  ProcessGroup* group = open(nullptr, nullptr, error, sizeof(error));
  if (!group) throw Error(std::string("--distributed: MPI did not start: ") + error);
  return std::unique_ptr<ProcessGroup>(group);  // the plugin stays loaded for the process
}

}  // namespace strata
