// Command-line plumbing shared by the subcommands: argument reading and the subcommands' entry
// points. Errors are thrown (InputError for bad arguments) and turned into exit codes in main.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/errors.h"

namespace cloth::app {

// Walks argv after the subcommand. Flags are "--name value" or "--name=value".
class Args {
public:
    Args(std::string command, std::vector<std::string> args);
    bool done() const { return pos_ >= args_.size(); }
    bool isFlag() const { return !done() && args_[pos_].rfind("--", 0) == 0; }
    std::string next();                       // the next argument, whatever it is
    std::string flag();                       // the next flag's name, "--steps"
    std::string value(const std::string& f);  // the flag's value; InputError if missing
    long positiveInt(const std::string& f);
    int positiveInt32(const std::string& f);  // at most 2^31 − 1, refused beyond
    [[noreturn]] void unknown(const std::string& f) const;
    // Takes the next argument as the scene file when it is not a flag (a second is an error).
    bool takeScene(std::string& scenePath);
    const std::string& command() const { return command_; }

private:
    std::string command_;
    std::vector<std::string> args_;
    size_t pos_ = 0;
    std::string pendingValue_;
    bool hasPending_ = false;
    bool sceneTaken_ = false;
};

// Outputs are checked before a run starts, so an unusable one is bad input (InputError naming the
// flag, the path and the reason: exit 2) rather than a failure after the simulation.
// A file: refused where model/output_file.h would refuse it (a directory, a socket, a folder that
// does not exist). Nothing for an empty path (the flag was not given).
void checkOutputFile(const std::string& flag, const std::string& file);
// A command's files, each (flag, path) with "SCENE" for its input: two that name one file (after
// ./, .. and symlinks) are refused, naming both, since the later write would replace the
// earlier output or the scene. Empty paths (flags not given) and devices or FIFOs, which are
// written through and never replaced, are skipped.
void checkDistinctFiles(const std::vector<std::pair<std::string, std::string>>& files);
// --frames DIR: made (with its parents) now, and refused if it is not a writable directory.
void prepareFramesDir(const std::string& flag, const std::string& dir);

// Appends a --set assignment; one that replaces an earlier one gets a notice on stderr (the
// later still wins).
// With `notices`, the notes go there for the caller to print (after --quiet is known).
void addSet(std::vector<std::string>& sets, std::string assignment,
            std::vector<std::string>* notices = nullptr);

int runCommand(Args& args);
int validateCommand(Args& args);
int infoCommand(Args& args);
int renderCommand(Args& args);   // cmd_render.cpp
int viewCommand(Args& args);     // cmd_view.cpp
int shadersCommand(Args& args);  // cmd_shaders.cpp: the assembled shaders, for CI

}  // namespace cloth::app
