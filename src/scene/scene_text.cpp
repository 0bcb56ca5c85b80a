#include "scene/scene_text.h"

#include <functional>
#include <vector>

#include "model/errors.h"
#include "scene/key_path.h"

namespace cloth {
namespace {

using Json = nlohmann::json;

// Follows the parser through the document so that an error inside a value (a number that
// overflows a double, 1e999) can still name its key path.
class PathTracker {
public:
    bool operator()(int, Json::parse_event_t event, Json& parsed) {
        using E = Json::parse_event_t;
        switch (event) {
            case E::object_start:
                push(false);
                break;
            case E::array_start:
                push(true);
                break;
            case E::key:
                frames_.back().key = parsed.get<std::string>();
                break;
            case E::object_end:
            case E::array_end:
                frames_.pop_back();
                completeElement();
                break;
            case E::value:
                completeElement();
                break;
        }
        return true;
    }
    std::string path() const {
        std::string p;
        for (const Frame& f : frames_)
            p = f.isArray ? element(p, f.count) : f.key.empty() ? p : child(p, f.key);
        return p;
    }

private:
    struct Frame {
        bool isArray;
        size_t count = 0;  // elements of an array completed so far = index of the current one
        std::string key;
    };
    void push(bool isArray) { frames_.push_back({isArray, 0, {}}); }
    void completeElement() {
        if (!frames_.empty() && frames_.back().isArray) ++frames_.back().count;
    }
    std::vector<Frame> frames_;
};

}  // namespace

Json parseSceneText(const std::string& text, const std::string& source) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw InputError(source, "", "the file is empty; expected a JSON object");
    PathTracker tracker;
    try {
        return Json::parse(text, std::ref(tracker));
    } catch (const Json::parse_error& e) {
        std::string what = e.what();
        const size_t cut = what.find("] ");  // drop nlohmann's "[json.exception...] " tag
        throw InputError(
            source, "",
            "not valid JSON: " + (cut == std::string::npos ? what : what.substr(cut + 2)));
    } catch (const Json::exception& e) {
        // Lexically valid but not representable, e.g. 1e999 overflows a double.
        std::string what = e.what();
        const size_t cut = what.find("] ");
        throw InputError(
            source, tracker.path(),
            "not a finite number: " + (cut == std::string::npos ? what : what.substr(cut + 2)));
    }
}

}  // namespace cloth
