#include "model/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdarg>
#include <cstring>
#include <filesystem>

namespace cloth {
namespace {

namespace fs = std::filesystem;

// Links followed before giving up, as the kernel does (ELOOP).
constexpr int kMaxLinks = 40;

OutputTarget unusable(std::string reason) {
    return {OutputTarget::Kind::Unusable, "", std::move(reason)};
}

std::string directoryOf(const std::string& file) {
    const fs::path dir = fs::path(file).parent_path();
    return dir.empty() ? "." : dir.string();
}

// `file` (a regular file, or a name not there yet) is replaced by a rename within its directory,
// which therefore has to exist and be writable.
OutputTarget replaceable(const std::string& file) {
    const std::string dir = directoryOf(file);
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0)
        return unusable("directory '" + dir + "': " + std::strerror(errno));
    if (!S_ISDIR(st.st_mode)) return unusable("'" + dir + "' is not a directory");
    if (::access(dir.c_str(), W_OK) != 0)
        return unusable("directory '" + dir + "' is not writable: " + std::strerror(errno));
    return {OutputTarget::Kind::Replace, file, ""};
}

}  // namespace

bool isFileNamePart(const std::string& part) {
    // 200 bytes leave room for the suffixes within a file name's 255 (NAME_MAX).
    return !part.empty() && part.size() <= 200 &&
           std::none_of(part.begin(), part.end(), [](char c) {
               return c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
           });
}

OutputTarget resolveOutput(const std::string& path) {
    if (path.empty()) return unusable("the path is empty");
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        // Opened by the path as given, so that links the kernel resolves itself
        // (/proc/self/fd/1 onto a pipe) work too.
        if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode))
            return {OutputTarget::Kind::WriteThrough, path, ""};
        if (S_ISDIR(st.st_mode)) return unusable("is a directory");
        if (!S_ISREG(st.st_mode))
            return unusable("is not a regular file, a FIFO or a character device");
    } else if (errno != ENOENT) {
        return unusable(std::strerror(errno));
    }
    // A regular file or a name not there yet (perhaps a dangling link's target): follow the
    // links, so the rename replaces the file they lead to and leaves them links.
    std::string file = path;
    for (int links = 0;; ++links) {
        if (::lstat(file.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) break;
        if (links == kMaxLinks) return unusable(std::strerror(ELOOP));
        std::error_code ec;
        const fs::path target = fs::read_symlink(file, ec);
        if (ec) return unusable(ec.message());
        file = target.is_absolute() ? target.string()
                                    : (fs::path(file).parent_path() / target).string();
    }
    return replaceable(file);
}

OutputFile::OutputFile(const std::string& path) : path_(path), target_(resolveOutput(path)) {
    int fd = -1;
    switch (target_.kind) {
        case OutputTarget::Kind::Unusable:
            throw OutputError(path_, target_.reason);
        case OutputTarget::Kind::WriteThrough:
            // No O_TRUNC, no O_CREAT: a device or a FIFO has nothing to truncate, and a path that
            // vanished since it was resolved is not made into a regular file here.
            fd = ::open(path_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
            break;
        case OutputTarget::Kind::Replace: {
            // A name of this process's own, made exclusively: two runs writing the same output
            // never write into each other's temporary file.
            for (int n = 0; fd < 0 && n < 100; ++n) {
                temporary_ = target_.file;
                temporary_ += ".tmp";
                temporary_ += std::to_string(::getpid());
                if (n > 0) {
                    temporary_ += '_';
                    temporary_ += std::to_string(n);
                }
                fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
                if (fd < 0 && errno != EEXIST) break;
            }
            // The replaced file keeps its permissions; a new one gets 0666 less the umask.
            struct stat st {};
            if (fd >= 0 && ::stat(target_.file.c_str(), &st) == 0) ::fchmod(fd, st.st_mode & 07777);
            break;
        }
    }
    if (fd < 0) {
        const int error = errno;
        temporary_.clear();  // not made: nothing to remove
        throw OutputError(path_, std::strerror(error));
    }
    file_ = ::fdopen(fd, "w");
    if (!file_) {
        const int error = errno;
        ::close(fd);
        if (!temporary_.empty()) std::remove(temporary_.c_str());
        throw OutputError(path_, std::strerror(error));
    }
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
    if (!temporary_.empty()) std::remove(temporary_.c_str());
}

void OutputFile::fail(int error) {
    if (error_ == 0) error_ = error ? error : EIO;
}

void OutputFile::print(const char* format, ...) {
    if (error_ || !file_) return;
    std::va_list args;
    va_start(args, format);
    const int n = std::vfprintf(file_, format, args);
    va_end(args);
    if (n < 0) fail(errno);
}

void OutputFile::write(const void* data, std::size_t size) {
    if (error_ || !file_ || size == 0) return;
    if (std::fwrite(data, 1, size, file_) != size) fail(errno);
}

void OutputFile::commit() {
    if (!file_) throw OutputError(path_, "already closed");
    if (!error_ && std::fflush(file_) != 0) fail(errno);
    if (!error_ && std::ferror(file_)) fail(EIO);
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) fail(errno);
    if (!error_ && !temporary_.empty()) {
        if (std::rename(temporary_.c_str(), target_.file.c_str()) != 0)
            fail(errno);
        else
            temporary_.clear();  // it is the target now
    }
    if (error_) {
        if (!temporary_.empty()) std::remove(temporary_.c_str());
        temporary_.clear();
        throw OutputError(path_, std::strerror(error_));
    }
}

void writeWholeFile(const std::string& path, const std::string& text) {
    OutputFile out(path);
    out.write(text);
    out.commit();
}

}  // namespace cloth
