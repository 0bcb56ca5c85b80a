// model/output_file.h: what a path names decides how it is written (a regular file replaced
// whole, a symlink's target replaced and the link kept, a FIFO or device written through,
// anything else refused), and a write that is not committed or that fails leaves the previous
// file as it was.
#include "model/output_file.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using Kind = OutputTarget::Kind;

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t entries(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputFile, ResolvesEachKindOfPath) {
    const fs::path d = test::freshTempDir("output_file_test", "resolve");
    { std::ofstream(d / "file") << "x"; }
    fs::create_directories(d / "sub");
    fs::create_symlink("sub/../file", d / "link");
    fs::create_symlink("link", d / "link2");  // a chain of links
    fs::create_symlink("sub/new", d / "dangling");
    ASSERT_EQ(::mkfifo((d / "fifo").c_str(), 0600), 0);

    EXPECT_EQ(resolveOutput((d / "file").string()).kind, Kind::Replace);
    EXPECT_EQ(resolveOutput((d / "new").string()).file, (d / "new").string());
    EXPECT_EQ(fs::path(resolveOutput((d / "link2").string()).file).lexically_normal(), d / "file");
    EXPECT_EQ(resolveOutput((d / "dangling").string()).file, (d / "sub/new").string());
    EXPECT_EQ(resolveOutput((d / "fifo").string()).kind, Kind::WriteThrough);
    EXPECT_EQ(resolveOutput("/dev/null").kind, Kind::WriteThrough);

    const OutputTarget dir = resolveOutput((d / "sub").string());
    EXPECT_EQ(dir.kind, Kind::Unusable);
    EXPECT_EQ(dir.reason, "is a directory");
    EXPECT_EQ(resolveOutput((d / "missing" / "x.csv").string()).kind, Kind::Unusable);
    const OutputTarget underFile = resolveOutput((d / "file" / "x.csv").string());
    EXPECT_EQ(underFile.kind, Kind::Unusable);
    EXPECT_NE(underFile.reason.find("Not a directory"), std::string::npos) << underFile.reason;

    // A socket: neither a file to replace nor something to write through.
    const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(s, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    const std::string sock = (d / "sock").string();
    if (sock.size() < sizeof addr.sun_path) {
        std::memcpy(addr.sun_path, sock.c_str(), sock.size() + 1);
        ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
        EXPECT_EQ(resolveOutput(sock).kind, Kind::Unusable);
    }
    ::close(s);
    fs::remove_all(d);
}

TEST(OutputFile, CommitReplacesTheFileAndKeepsItsPermissions) {
    const fs::path d = test::freshTempDir("output_file_test", "replace");
    { std::ofstream(d / "out.txt") << "previous\n"; }
    fs::permissions(d / "out.txt", fs::perms(0640));
    OutputFile out((d / "out.txt").string());
    out.print("%d %s\n", 42, "new");
    EXPECT_EQ(slurp(d / "out.txt"), "previous\n");  // nothing visible before the commit
    out.commit();
    EXPECT_EQ(slurp(d / "out.txt"), "42 new\n");
    EXPECT_EQ(fs::status(d / "out.txt").permissions(), fs::perms(0640));
    EXPECT_EQ(entries(d), 1u);
    fs::remove_all(d);
}

TEST(OutputFile, WithoutCommitThePreviousFileStaysAndNoTemporaryIsLeft) {
    const fs::path d = test::freshTempDir("output_file_test", "abandon");
    { std::ofstream(d / "out.txt") << "previous\n"; }
    {
        OutputFile out((d / "out.txt").string());
        out.write("half a fi");
    }
    EXPECT_EQ(slurp(d / "out.txt"), "previous\n");
    EXPECT_EQ(entries(d), 1u);
    fs::remove_all(d);
}

TEST(OutputFile, FailedWriteThrowsNamingThePathAndTheReason) {
    struct stat st {};
    if (::stat("/dev/full", &st) != 0 || !S_ISCHR(st.st_mode)) GTEST_SKIP() << "no /dev/full";
    OutputFile out("/dev/full");
    out.write(std::string(100000, 'x'));  // more than a stdio buffer: a write fails here
    try {
        out.commit();
        FAIL() << "no exception";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("No space"), std::string::npos) << e.what();
    }
    ASSERT_EQ(::lstat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputFile, UnusablePathThrowsOutputError) {
    const fs::path d = test::freshTempDir("output_file_test", "unusable");
    EXPECT_THROW(OutputFile(d.string()), OutputError);
    EXPECT_THROW(writeWholeFile((d / "missing" / "x").string(), "x"), OutputError);
    fs::remove_all(d);
}

}  // namespace
}  // namespace cloth
