// Command-line plumbing shared by the subcommands: argument reading and the subcommands' entry
// points. Errors are thrown (InputError for bad arguments) and turned into exit codes in main.
#pragma once

#include <string>
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

int runCommand(Args& args);
int validateCommand(Args& args);
int infoCommand(Args& args);
int renderCommand(Args& args);   // cmd_render.cpp
int viewCommand(Args& args);     // cmd_view.cpp
int shadersCommand(Args& args);  // cmd_shaders.cpp: the assembled shaders, for CI

}  // namespace cloth::app
