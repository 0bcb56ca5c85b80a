#include "support/bad_scenes.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

namespace cloth::test {

void PrintTo(const BadScene& b, std::ostream* os) {
    *os << b.file;
}

std::string readFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<BadScene> loadManifest() {
    std::vector<BadScene> list;
    const auto manifest = nlohmann::json::parse(readFile(kBadDir / "expected.json"));
    for (const auto& [file, key] : manifest.items()) {
        if (file.front() == '_') continue;  // _comment
        BadScene b{file, {}};
        if (key.is_array()) {
            for (const auto& k : key) b.keys.push_back(k.get<std::string>());
        } else if (!key.get<std::string>().empty()) {
            b.keys.push_back(key.get<std::string>());
        }
        list.push_back(b);
    }
    return list;
}

}  // namespace cloth::test
