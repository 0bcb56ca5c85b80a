// Errors that reach the user. src/app turns each into a message and an exit code (DESIGN.md §5).
#pragma once

#include <stdexcept>
#include <string>

namespace cloth {

// Exit codes of DESIGN.md §5.
enum ExitCode { kOk = 0, kInternal = 1, kInvalidInput = 2, kUnstable = 3, kNoGpu = 4 };

// Bad input: a scene file, a --set override or a command-line argument. Exit code 2.
class InputError : public std::runtime_error {
public:
    InputError(std::string file, std::string key, std::string reason)
        : std::runtime_error(format(file, key, reason)),
          file_(std::move(file)),
          key_(std::move(key)),
          reason_(std::move(reason)) {}

    const std::string& file() const { return file_; }
    const std::string& key() const { return key_; }
    const std::string& reason() const { return reason_; }

private:
    static std::string format(const std::string& file, const std::string& key,
                              const std::string& reason) {
        std::string m = file.empty() ? std::string() : file + ": ";
        if (!key.empty()) m += key + ": ";
        return m + reason;
    }
    std::string file_, key_, reason_;
};

// The GPU backend was asked for but no usable GL 4.3+ context exists. Exit code 4.
class GpuUnavailable : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace cloth
