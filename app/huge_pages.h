// Large allocations in transparent huge pages, for the whole process.
//
// Exports allocate and touch hundreds of megabytes that they free again a moment later (the
// tiles' arrays, the mesh, the file read back). Each first touch of a 4 KiB page is a page
// fault; where faults are slow (virtual machines: 0.25 s for 50 MB on our CI's machine, a
// quarter of an export) that cost dominates the host-side stages. glibc's malloc can ask the
// kernel for transparent huge pages on its large chunks (tunable glibc.malloc.hugetlb=1, glibc
// 2.35 and later), one fault per 2 MiB instead of 512, but reads its tunables only when the
// process starts. So main() calls this first: unless GLIBC_TUNABLES already names the tunable
// (or STRATA_HUGE_PAGES=0), it adds it and re-executes the same binary with the same
// arguments. Where exec fails, or on a libc that is not glibc, it returns and nothing changes;
// where the kernel offers no huge pages, the tunable changes nothing.
#pragma once

namespace strata {

// Returns only when the process goes on as it is (see above). Call before any thread starts.
void restartWithHugePageMalloc(char** argv);

}  // namespace strata
