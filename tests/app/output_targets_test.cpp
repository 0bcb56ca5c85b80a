// What an output path names decides how `run` writes it (README, "Reading the output"): a regular
// file is replaced whole through a temporary file and a rename; a symlink writes its target the
// same way and stays a link; a FIFO or a character device is written through, never replaced; a
// write that fails exits 1 naming the file and the reason. A --frames DIR that cannot be a
// directory is exit 2 before any step runs.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kChain = CLOTH_SOURCE_DIR "/scenes/chain.json";  // 1×3: a 4-line CSV

fs::path tempDir(const std::string& name) {
    return test::freshTempDir("output_targets_test", name);
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

test::ProcessResult runWithCsv(const std::string& csv) {
    return runProcess({kExe, "run", kChain, "--steps", "10", "--quiet", "--out-csv", csv}, 60);
}

bool isCsv(const std::string& text) {
    return text.rfind("i,j,x,y,z,vx,vy,vz\n", 0) == 0 && text.back() == '\n';
}

TEST(OutputTargets, RegularFileIsReplacedWholeAndNoTemporaryIsLeft) {
    const fs::path d = tempDir("regular");
    { std::ofstream(d / "out.csv") << "previous\n"; }
    const auto r = runWithCsv((d / "out.csv").string());
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(d / "out.csv")));
    EXPECT_TRUE(isCsv(slurp(d / "out.csv"))) << slurp(d / "out.csv");
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
    fs::remove_all(d);
}

// A relative link is resolved from the link's folder, not the working directory.
TEST(OutputTargets, SymlinkWritesItsTargetAndStaysALink) {
    const fs::path d = tempDir("symlink");
    fs::create_directories(d / "data");
    { std::ofstream(d / "data" / "target.csv") << "previous\n"; }
    fs::create_symlink("data/target.csv", d / "link.csv");
    const auto r = runWithCsv((d / "link.csv").string());
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    ASSERT_TRUE(fs::is_symlink(d / "link.csv"));
    EXPECT_EQ(fs::read_symlink(d / "link.csv"), fs::path("data/target.csv"));
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(d / "data" / "target.csv")));
    EXPECT_TRUE(isCsv(slurp(d / "data" / "target.csv"))) << slurp(d / "data" / "target.csv");
    // The temporary file went beside the target and was renamed onto it: nothing else is left.
    EXPECT_EQ(std::distance(fs::directory_iterator(d / "data"), fs::directory_iterator()), 1);
    fs::remove_all(d);
}

// A link whose target does not exist yet: the target is made, the link kept.
TEST(OutputTargets, DanglingSymlinkCreatesItsTarget) {
    const fs::path d = tempDir("dangling");
    fs::create_symlink("new.csv", d / "link.csv");
    const auto r = runWithCsv((d / "link.csv").string());
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    ASSERT_TRUE(fs::is_symlink(d / "link.csv"));
    EXPECT_TRUE(isCsv(slurp(d / "new.csv")));
    fs::remove_all(d);
}

// Reads a FIFO from a thread until its writer closes it, giving up at a deadline so that a
// writer which never opens it (the FIFO replaced instead) fails the test rather than hangs it.
class FifoReader {
public:
    explicit FifoReader(const fs::path& path) {
        // O_NONBLOCK: opening for reading returns at once, so the writer's open does not wait.
        fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
        if (fd_ >= 0) thread_ = std::thread([this] { run(); });
    }
    ~FifoReader() {
        stop_ = true;
        if (thread_.joinable()) thread_.join();
        if (fd_ >= 0) ::close(fd_);
    }
    bool opened() const { return fd_ >= 0; }
    // Everything read: waits for the writer to close, or until `seconds` pass.
    std::string text(double seconds) {
        const auto deadline =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (!done_ && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        stop_ = true;
        if (thread_.joinable()) thread_.join();
        return text_;
    }

private:
    void run() {
        char buf[4096];
        while (!stop_) {
            const ssize_t n = ::read(fd_, buf, sizeof buf);
            if (n > 0) {
                text_.append(buf, size_t(n));
            } else if (n == 0 && !text_.empty()) {
                break;  // the writer wrote and closed
            } else {
                std::this_thread::sleep_for(std::chrono::milliseconds(5));  // no writer yet
            }
        }
        done_ = true;
    }
    int fd_ = -1;
    std::thread thread_;
    std::atomic<bool> stop_{false}, done_{false};
    std::string text_;
};

TEST(OutputTargets, FifoIsWrittenThroughNotReplaced) {
    const fs::path d = tempDir("fifo");
    const fs::path fifo = d / "pipe.csv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    FifoReader reader(fifo);
    ASSERT_TRUE(reader.opened());
    const auto r = runWithCsv(fifo.string());
    const std::string text = reader.text(30);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo))) << "the FIFO was replaced";
    EXPECT_TRUE(!text.empty() && isCsv(text)) << "read through the FIFO: '" << text << "'";
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
    fs::remove_all(d);
}

// /dev/full accepts the open and fails every write with ENOSPC: the run must say so and fail,
// and the device must still be the device (writing through it, not replacing it).
TEST(OutputTargets, FailedWriteToACharacterDeviceExitsOneNamingThePathAndTheReason) {
    struct stat st {};
    if (::stat("/dev/full", &st) != 0 || !S_ISCHR(st.st_mode)) GTEST_SKIP() << "no /dev/full";
    const auto r = runWithCsv("/dev/full");
    EXPECT_EQ(r.exitCode, 1) << test::describe(r);
    EXPECT_NE(r.err.find("/dev/full"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("No space"), std::string::npos) << r.err;
    ASSERT_EQ(::lstat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
}

// /dev/null is written through too (and a run that writes there succeeds).
TEST(OutputTargets, DevNullIsWrittenThrough) {
    struct stat st {};
    if (::stat("/dev/null", &st) != 0 || !S_ISCHR(st.st_mode)) GTEST_SKIP() << "no /dev/null";
    const auto r = runWithCsv("/dev/null");
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    ASSERT_EQ(::lstat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null was replaced";
}

// A directory cannot be an output file: bad input, found before the run.
TEST(OutputTargets, DirectoryIsRefusedAsInput) {
    const fs::path d = tempDir("directory");
    const auto r = runWithCsv(d.string());
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find(d.string()), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_directory(d));
    fs::remove_all(d);
}

test::ProcessResult runWithFrames(const std::string& dir) {
    return runProcess({kExe, "run", kChain, "--steps", "10", "--every", "5", "--frames", dir}, 60);
}

TEST(OutputTargets, FramesUnderARegularFileIsExitTwoBeforeAnyStep) {
    const fs::path d = tempDir("frames_file");
    { std::ofstream(d / "file") << "not a folder\n"; }
    const std::string frames = (d / "file" / "frames").string();
    const auto r = runWithFrames(frames);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(frames), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Not a directory"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");  // no summary: nothing ran
    EXPECT_EQ(slurp(d / "file"), "not a folder\n");
    fs::remove_all(d);
}

TEST(OutputTargets, FramesNamingARegularFileIsExitTwo) {
    const fs::path d = tempDir("frames_is_file");
    { std::ofstream(d / "file") << "not a folder\n"; }
    const auto r = runWithFrames((d / "file").string());
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find((d / "file").string()), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    fs::remove_all(d);
}

// The tests run as root, to whom permission bits deny nothing: /proc is a place where no
// directory can be made whoever asks.
TEST(OutputTargets, FramesWhereNoDirectoryCanBeMadeIsExitTwoBeforeAnyStep) {
    const std::string frames = "/proc/clothsim-no-such-dir/frames";
    const auto r = runWithFrames(frames);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find(frames), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

// Nothing lost: two outputs naming one file (however the path is written: ./x, a/../x, a
// symlink), or an output naming the scene, are exit 2 before any step, naming both flags, and
// every file stays as it was. /dev/null given twice is written through twice, never replaced.
TEST(OutputTargets, OutputsNamingOneFileOrTheSceneAreExitTwoAndLoseNothing) {
    const fs::path d = tempDir("one_file");
    const fs::path scene = d / "scene.json", csv = d / "out.csv";
    fs::copy_file(kChain, scene);
    fs::create_directory(d / "sub");
    fs::create_symlink(csv, d / "link.csv");
    const std::string text = slurp(scene);
    { std::ofstream(csv) << "previous\n"; }
    const std::vector<std::vector<std::string>> cases = {
        {"--out-csv", scene.string()},
        {"--out-csv", csv.string(), "--out-obj", (d / "." / "out.csv").string()},
        {"--out-csv", csv.string(), "--out-solves", (d / "sub" / ".." / "out.csv").string()},
        {"--out-csv", (d / "link.csv").string(), "--out-colliders", csv.string()},
        {"--out-pc2", (d / "cache.pc2").string(), "--out-csv", (d / "cache.obj").string()},
    };
    for (const std::vector<std::string>& outputs : cases) {
        std::vector<std::string> command = {kExe, "run", scene.string(), "--steps", "10"};
        command.insert(command.end(), outputs.begin(), outputs.end());
        const auto r = runProcess(command, 60);
        EXPECT_EQ(r.exitCode, 2) << outputs[1] << ": " << test::describe(r);
        EXPECT_NE(r.err.find("give each output a file of its own"), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(slurp(scene), text);
        EXPECT_EQ(slurp(csv), "previous\n");
        EXPECT_FALSE(fs::exists(d / "cache.pc2"));
    }
    const auto r = runProcess({kExe, "run", scene.string(), "--steps", "10", "--quiet", "--out-csv",
                               "/dev/null", "--out-obj", "/dev/null"},
                              60);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    fs::remove_all(d);
}

}  // namespace
}  // namespace cloth
