// libFuzzer entry for the scene loader (scripts/fuzz.sh). Any input may be refused with an
// InputError; any other exception, a crash, a sanitizer report or a hang is a finding.
//
// Input: the scene text, optionally followed by NUL-separated --set overrides
// ("KEY.PATH=JSON"), so the override parser is fuzzed along with the scene.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/errors.h"
#include "scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const size_t end = input.find('\0');
    const std::string text = input.substr(0, end);
    std::vector<std::string> overrides;
    for (size_t at = end; at != std::string::npos && at < input.size();) {
        const size_t next = input.find('\0', at + 1);
        overrides.push_back(input.substr(at + 1, next == std::string::npos ? next : next - at - 1));
        at = next;
    }
    try {
        cloth::parseScene(text, "fuzz", overrides);
    } catch (const cloth::InputError&) {
        // The one way to refuse a scene.
    }
    return 0;
}
