// Runs a child process for the command-line tests, capturing its stdout and stderr, and tells
// an exit from a crash (a signal) or a hang (killed at the timeout).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cloth::test {

struct ProcessResult {
    int exitCode = -1;      // the exit status, or -1 when the child did not exit normally
    std::string out, err;   // everything the child wrote to stdout and stderr
    bool crashed = false;   // killed by a signal it did not ask for (SIGSEGV, SIGABRT, ...)
    bool timedOut = false;  // still running at the timeout, then killed
    int signal = 0;         // the signal that ended it, if any
    double seconds = 0;     // wall time
};

struct ProcessOptions {
    double timeoutSeconds = 60;
    // RLIMIT_AS for the child [bytes], 0 = inherit: an allocation past it fails instead of
    // succeeding lazily, so "refused before allocating" can be told from "allocated, then died".
    std::uint64_t addressSpaceLimit = 0;
};

ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options);
ProcessResult runProcess(const std::vector<std::string>& argv, double timeoutSeconds);

// "exit 2" / "signal 11 (crashed)" / "timed out": for assertion messages, with stderr appended.
std::string describe(const ProcessResult& r);

// An empty folder temp/clothsim_<suite>_<name>_<pid>, made afresh: one per process and test,
// so tests that ctest runs side by side never share one. It is removed at the end of the test
// that made it (made in SetUpTestSuite: of its suite) unless that failed; after a failure it is
// kept, and its path printed, for inspection.
std::filesystem::path freshTempDir(const std::string& suite, const std::string& name);

// The running test's own folder, freshTempDir(<suite>, <test>) ('/' of parameterised names as
// '_'): made at the test's first call, the same folder at the next ones.
std::filesystem::path testTempDir();

}  // namespace cloth::test
