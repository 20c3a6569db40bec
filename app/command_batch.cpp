// `strata batch FILE`: the command lines of FILE run one after the other in this one process.
//
// What a process starts once is then paid once for a whole list of jobs: the CUDA driver's start
// (about 0.3 s a process on an H200, more than a 512-cell Boolean takes on it), the worker
// threads, the huge-page allocator. Each job runs as the command would alone (beginCommand puts
// the process-wide settings back first), with its own exit code.
//
// FILE: one command a line, as typed after `strata` (a leading `strata` is allowed), words split
// as a POSIX shell splits them without expansions: blanks separate words, '...' keeps its text
// as it is, "..." keeps its text but for \" \\ \$ \` and a line break, a backslash outside
// quotes keeps the next character; a word starting with # begins a comment to the line's end.
// No variables, globs or redirections: paths relative to the current folder. Every line is read
// and checked before the first job runs, so that a typo on line 40 does not leave 39 jobs done
// and the rest not.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli_common.h"
#include "app/commands.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {

struct Job {
  int line = 0;
  std::vector<std::string> words;
};

// The words of one line, or strata::Error saying what is wrong with it (an unfinished quote).
std::vector<std::string> splitWords(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool inWord = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      if (inWord) words.push_back(word);
      word.clear();
      inWord = false;
      continue;
    }
    if (c == '#' && !inWord) break;  // a comment
    inWord = true;
    if (c == '\\') {
      if (i + 1 >= line.size()) throw Error("a backslash ends the line (lines do not continue)");
      word += line[++i];
    } else if (c == '\'') {
      const size_t end = line.find('\'', i + 1);
      if (end == std::string::npos) throw Error("a single quote (') is not closed");
      word += line.substr(i + 1, end - i - 1);
      i = end;
    } else if (c == '"') {
      size_t j = i + 1;
      for (; j < line.size() && line[j] != '"'; ++j) {
        if (line[j] == '\\' && j + 1 < line.size() &&
            std::string("\"\\$`").find(line[j + 1]) != std::string::npos)
          ++j;
        word += line[j];
      }
      if (j >= line.size()) throw Error("a double quote (\") is not closed");
      i = j;
    } else {
      word += c;
    }
  }
  if (inWord) words.push_back(word);
  return words;
}

// The commands a batch may run: those of the command line that end on their own.
bool batchable(const std::string& command) {
  for (const char* c : {"eval", "boolean", "export", "offset", "shell", "round", "render"})
    if (command == c) return true;
  return false;
}

// Every job of `path` ("-": standard input), checked. Throws strata::Error naming the file and
// the line.
std::vector<Job> readJobs(const std::string& path) {
  // A file through readWholeFile: FIFOs, devices, folders and files past --max-file-size are
  // refused with a reason (a FIFO hung the batch).
  std::istringstream file(path == "-" ? std::string() : readWholeFile(path));
  std::istream& in = path == "-" ? std::cin : file;
  const std::string name = path == "-" ? "standard input" : path;
  std::vector<Job> jobs;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = name + ":" + std::to_string(number) + ": ";
    std::vector<std::string> words;
    try {
      words = splitWords(line);
    } catch (const Error& e) {
      throw Error(where + e.what());
    }
    if (!words.empty() && words[0] == "strata") words.erase(words.begin());
    if (words.empty()) continue;
    if (!batchable(words[0]))
      throw Error(where + "'" + words[0] +
                  "' cannot run in a batch (eval, boolean, export, offset, shell, round and "
                  "render can)");
    for (const std::string& w : words)
      if (w == "--distributed")
        throw Error(where + "--distributed cannot run in a batch (run it under mpirun alone)");
    jobs.push_back(Job{number, std::move(words)});
  }
  if (in.bad()) throw Error(name + ": reading failed");
  if (jobs.empty()) throw Error(name + ": no commands in it");
  return jobs;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

std::string lineList(const std::vector<int>& lines) {
  std::string out;
  for (size_t i = 0; i < lines.size() && i < 10; ++i)
    out += (i ? ", " : "") + std::to_string(lines[i]);
  if (lines.size() > 10) out += " and " + std::to_string(lines.size() - 10) + " more";
  return out;
}

}  // namespace

int runBatch(const std::vector<std::string>& args,
             const std::function<int(const std::vector<std::string>&)>& runOne) {
  std::vector<std::string> files;
  bool keepGoing = false, quiet = false;
  for (const std::string& a : args) {
    if (a == "--keep-going" || a == "-k") {
      keepGoing = true;
    } else if (a == "-q" || a == "--quiet") {
      quiet = true;
    } else if (a.size() > 1 && a[0] == '-') {
      std::fprintf(stderr, "strata: error: batch: unknown option '%s'\n", a.c_str());
      return 2;
    } else {
      files.push_back(a);
    }
  }
  if (files.size() != 1) {
    std::fprintf(stderr,
                 "strata: error: batch takes one file of commands (- for standard input), "
                 "given %zu\n",
                 files.size());
    return 2;
  }
  std::vector<Job> jobs;
  const int read = runGuarded([&] {
    jobs = readJobs(files[0]);
    return 0;
  });
  if (read != 0) return read;

  const auto start = std::chrono::steady_clock::now();
  std::vector<int> failedLines;
  int firstFailure = 0;
  size_t run = 0;
  for (const Job& job : jobs) {
    if (!quiet)
      std::fprintf(stderr, "strata batch: job %zu of %zu (line %d): %s\n", run + 1, jobs.size(),
                   job.line, joined(job.words).c_str());
    std::fflush(stderr);
    beginCommand();
    const int code = runOne(job.words);
    std::fflush(stdout);
    ++run;
    if (code == 0) continue;
    failedLines.push_back(job.line);
    if (firstFailure == 0) firstFailure = code;
    if (code >= 128) {  // cancelled (a signal): the batch ends with it
      std::fprintf(stderr, "strata batch: cancelled at line %d; %zu job%s after it not run\n",
                   job.line, jobs.size() - run, jobs.size() - run == 1 ? "" : "s");
      return code;
    }
    if (!keepGoing) break;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (failedLines.empty()) {
    if (!quiet)
      std::fprintf(stderr, "strata batch: %zu jobs in %.2f s, all succeeded\n", jobs.size(),
                   seconds);
    return 0;
  }
  std::fprintf(stderr, "strata batch: %zu of %zu jobs run in %.2f s; failed: line%s %s", run,
               jobs.size(), seconds, failedLines.size() > 1 ? "s" : "",
               lineList(failedLines).c_str());
  if (run < jobs.size())
    std::fprintf(stderr, "; the %zu after it not run (--keep-going runs them)", jobs.size() - run);
  std::fprintf(stderr, "\n");
  return firstFailure;
}

}  // namespace strata
