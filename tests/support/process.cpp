#include "support/process.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace cloth::test {
namespace {

using Clock = std::chrono::steady_clock;

void closeFd(int& fd) {
    if (fd >= 0) close(fd);
    fd = -1;
}

// Reads whatever is ready on `fd` into `sink`; closes it at end of file.
void drain(int& fd, std::string& sink) {
    char buf[65536];
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n > 0) {
        sink.append(buf, size_t(n));
    } else if (n == 0 || (errno != EINTR && errno != EAGAIN)) {
        closeFd(fd);
    }
}

}  // namespace

ProcessResult runProcess(const std::vector<std::string>& argv, const ProcessOptions& options) {
    if (argv.empty()) throw std::invalid_argument("runProcess: empty argv");
    // Everything the child needs is built before fork: after it only async-signal-safe calls.
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0 || pipe2(errPipe, O_CLOEXEC) != 0)
        throw std::runtime_error("runProcess: pipe failed");

    const auto start = Clock::now();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("runProcess: fork failed");
    if (pid == 0) {
        const int devNull = open("/dev/null", O_RDONLY);
        if (devNull >= 0) dup2(devNull, STDIN_FILENO);
        dup2(outPipe[1], STDOUT_FILENO);
        dup2(errPipe[1], STDERR_FILENO);
        if (options.addressSpaceLimit > 0) {
            const rlimit lim{options.addressSpaceLimit, options.addressSpaceLimit};
            setrlimit(RLIMIT_AS, &lim);
        }
        execv(args[0], args.data());
        const char msg[] = "runProcess: exec failed\n";
        (void)!write(STDERR_FILENO, msg, sizeof msg - 1);
        _exit(127);
    }
    close(outPipe[1]);
    close(errPipe[1]);

    ProcessResult r;
    int fds[2] = {outPipe[0], errPipe[0]};
    const auto deadline = start + std::chrono::duration<double>(options.timeoutSeconds);
    while (fds[0] >= 0 || fds[1] >= 0) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
        if (left.count() <= 0) {
            r.timedOut = true;
            kill(pid, SIGKILL);
            break;
        }
        pollfd p[2] = {{fds[0], POLLIN, 0}, {fds[1], POLLIN, 0}};
        if (poll(p, 2, int(left.count())) < 0 && errno != EINTR) break;
        if (fds[0] >= 0 && p[0].revents) drain(fds[0], r.out);
        if (fds[1] >= 0 && p[1].revents) drain(fds[1], r.err);
    }
    closeFd(fds[0]);
    closeFd(fds[1]);

    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (WIFEXITED(status)) {
        r.exitCode = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        r.signal = WTERMSIG(status);
        r.crashed = !r.timedOut;
    }
    return r;
}

ProcessResult runProcess(const std::vector<std::string>& argv, double timeoutSeconds) {
    ProcessOptions options;
    options.timeoutSeconds = timeoutSeconds;
    return runProcess(argv, options);
}

std::string describe(const ProcessResult& r) {
    std::string s;
    if (r.timedOut) {
        s = "timed out after " + std::to_string(r.seconds) + " s";
    } else if (r.signal != 0) {
        s = "killed by signal " + std::to_string(r.signal) + " (" + strsignal(r.signal) + ")";
    } else {
        s = "exit " + std::to_string(r.exitCode);
    }
    return s + "\n--- stderr ---\n" + r.err.substr(0, 4000) + "\n--- stdout ---\n" +
           r.out.substr(0, 2000);
}

namespace {

// Removes the folders freshTempDir made once their owner has ended without failing: a test's at
// its end, a suite's (made outside any test, in SetUpTestSuite) at the suite's end.
class TempDirCleanup : public ::testing::EmptyTestEventListener {
public:
    void made(const std::filesystem::path& d) { (inTest_ ? testDirs_ : suiteDirs_).push_back(d); }

    std::filesystem::path testDir() {
        if (testDir_.empty()) {
            const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
            if (info == nullptr) throw std::logic_error("testTempDir() called outside a test");
            const auto flat = [](std::string s) {
                for (char& c : s) c = c == '/' ? '_' : c;
                return s;
            };
            testDir_ = freshTempDir(flat(info->test_suite_name()), flat(info->name()));
        }
        return testDir_;
    }

private:
    void OnTestStart(const ::testing::TestInfo&) override { inTest_ = true; }
    void OnTestEnd(const ::testing::TestInfo& info) override {
        inTest_ = false;
        testDir_.clear();
        settle(testDirs_, info.result()->Failed());
    }
    void OnTestSuiteEnd(const ::testing::TestSuite& suite) override {
        settle(suiteDirs_, suite.Failed());
    }

    static void settle(std::vector<std::filesystem::path>& dirs, bool failed) {
        for (const auto& d : dirs) {
            std::error_code ignored;
            if (!failed) {
                std::filesystem::remove_all(d, ignored);
            } else {
                std::cerr << "kept for inspection: " << d.string() << "\n";
            }
        }
        dirs.clear();
    }

    bool inTest_ = false;
    std::filesystem::path testDir_;
    std::vector<std::filesystem::path> testDirs_;
    std::vector<std::filesystem::path> suiteDirs_;
};

TempDirCleanup& tempDirCleanup() {
    // gtest owns the listener once appended; it lives until the program ends.
    static TempDirCleanup* const cleanup = [] {
        auto* c = new TempDirCleanup;
        ::testing::UnitTest::GetInstance()->listeners().Append(c);
        return c;
    }();
    return *cleanup;
}

// Listening from the start, so that a folder made in the first test counts as that test's.
[[maybe_unused]] const bool kCleanupListening = (tempDirCleanup(), true);

}  // namespace

std::filesystem::path freshTempDir(const std::string& suite, const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() /
                       ("clothsim_" + suite + "_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    tempDirCleanup().made(d);
    return d;
}

std::filesystem::path testTempDir() {
    return tempDirCleanup().testDir();
}

}  // namespace cloth::test
