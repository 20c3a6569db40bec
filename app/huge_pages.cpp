#include "app/huge_pages.h"

#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <unistd.h>
#endif

namespace strata {

void restartWithHugePageMalloc(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  constexpr const char* kTunable = "glibc.malloc.hugetlb";
  const char* off = std::getenv("STRATA_HUGE_PAGES");
  if (off && std::strcmp(off, "0") == 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, kTunable)) return;  // set, by us or by the user
  std::string value = tunables && *tunables ? std::string(tunables) + ":" : std::string();
  value += std::string(kTunable) + "=1";
  if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);  // returns only on failure: go on without
  ::unsetenv("GLIBC_TUNABLES");
  if (tunables) ::setenv("GLIBC_TUNABLES", tunables, 1);
#else
  (void)argv;
#endif
}

}  // namespace strata
