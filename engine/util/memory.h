// Process memory, and the room left for more, as the operating system sees it.
#pragma once

#include <cstdint>
#include <string>

namespace strata {

// Peak resident set size of this process so far, in bytes (0 where unknown).
uint64_t peakResidentBytes();

// Resident set size of this process now, in bytes (the peak where unknown): what a job's
// estimate adds its own memory to. The peak so far would count what an earlier job held and let
// go: an editor's estimates grew by a third from one export to the next of the same scene (an
// artist's test), and could refuse a job that fits.
uint64_t residentBytes();

// Memory the system can still give this process without swapping, in bytes: MemAvailable, or
// less where `ulimit -v` or the process's control group allows less; 0 where unknown.
uint64_t availableMemoryBytes();

// Free space for an unprivileged writer in the file system holding `folder`, in bytes; 0 where
// unknown (the folder does not exist, ...).
uint64_t freeDiskBytes(const std::string& folder);
// The same for the folder a file at `path` lives (or would live) in.
uint64_t freeDiskBytesForFile(const std::string& path);

}  // namespace strata
