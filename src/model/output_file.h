// Every file the program writes goes through OutputFile (DESIGN.md §5, README "Reading the
// output"). What the path names decides how:
//   - a regular file, or a name not there yet: written to a temporary file beside it and renamed
//     onto it on commit, so a failed or interrupted write never leaves half a file or clobbers the
//     previous one;
//   - a symlink: its target, the same way (the temporary beside the target, the link kept);
//   - a FIFO or a character device (/dev/null, a terminal): opened and written directly, never
//     replaced (opening a FIFO waits, like any writer, until something reads it);
//   - anything else (a directory, a socket, a block device, a folder that does not exist):
//     refused.
// Every write, the flush and the close are checked: a failure (a full disk) throws OutputError
// naming the path and the reason, and a regular target keeps its previous content.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace cloth {

// An output file could not be written: a write, the flush, the close or the rename failed (a
// full disk), or the path names nothing a file can be written to. Exit code 1 (main turns every
// runtime_error into it); the message names the file as given and the reason. An output the
// command line can check before a run starts is refused there instead, as bad input (exit 2).
class OutputError : public std::runtime_error {
public:
    OutputError(const std::string& path, const std::string& reason)
        : std::runtime_error("cannot write " + path + ": " + reason) {}
};

// How an output path would be written, found without writing anything: the command line checks
// its outputs with it before a run starts.
struct OutputTarget {
    enum class Kind { Replace, WriteThrough, Unusable };
    Kind kind = Kind::Unusable;
    std::string file;    // Replace: the file renamed onto (a symlink's final target)
    std::string reason;  // Unusable: why, e.g. "is a directory"
};
OutputTarget resolveOutput(const std::string& path);

// Whether `part` may start a file name inside a folder the user gave (a scene's name in --frames,
// a bench's --label): not empty, at most 200 bytes (a file name holds 255 with the suffixes), no
// '/' or '\' that would leave the folder, no control character that would break a line of the
// files that quote it (the OBJ's object line).
bool isFileNamePart(const std::string& part);

class OutputFile {
public:
    // Opens the path as resolveOutput says; OutputError if it is unusable or cannot be opened.
    explicit OutputFile(const std::string& path);
    // Without commit(): the temporary file is removed and the target left as it was.
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    // After the first failed write the rest are skipped; commit() reports it.
    void print(const char* format, ...) __attribute__((format(printf, 2, 3)));
    void write(const void* data, std::size_t size);
    void write(const std::string& text) { write(text.data(), text.size()); }

    // Flushes, closes and (for a replaced file) renames into place; OutputError if any write,
    // the flush, the close or the rename failed.
    void commit();

private:
    void fail(int error);
    std::string path_;  // as given: what messages name
    OutputTarget target_;
    std::string temporary_;  // Replace only
    std::FILE* file_ = nullptr;
    int error_ = 0;  // errno of the first failure
};

// The whole of `text` as the file `path`, through OutputFile.
void writeWholeFile(const std::string& path, const std::string& text);

}  // namespace cloth
