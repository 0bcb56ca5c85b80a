#include "scene/scene_text.h"

#include <cctype>
#include <functional>
#include <map>
#include <vector>

#include "model/errors.h"
#include "scene/key_path.h"

namespace cloth {
namespace {

using Json = nlohmann::json;

// A key given twice in one object: nlohmann keeps the last silently, which would drop the first
// value without a word ({"bend": 100, "bend": 0} switches the bend family off).
struct DuplicateKey {
    std::string path;
    size_t first, second;  // the keys' places in document order (0 = the document's first key)
};

// The line of the document's n-th key (0-based, in document order): the parser's callback
// knows keys but not positions, so the text is walked once more when a complaint needs them.
// A string followed by ':' is a key; comments are not JSON, so a quote always opens a string.
int lineOfKey(const std::string& text, size_t n) {
    int line = 1;
    size_t keys = 0;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n') ++line;
        if (text[i] != '"') continue;
        const int start = line;
        for (++i; i < text.size() && text[i] != '"'; ++i) {
            if (text[i] == '\\')
                ++i;
            else if (text[i] == '\n')
                ++line;
        }
        size_t k = i + 1;
        while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
        if (k < text.size() && text[k] == ':' && keys++ == n) return start;
    }
    return 0;
}

// A document nested deeper than kMaxDepth arrays and objects: a scene needs a handful, and a
// path of a million levels took the parser's callbacks minutes and a message of megabytes.
constexpr std::size_t kMaxDepth = 64;
struct TooDeep {
    std::string path;  // where it went past kMaxDepth
};

// Follows the parser through the document so that an error inside a value (a number that
// overflows a double, 1e999) can still name its key path, and refuses a duplicate key and a
// nesting deeper than kMaxDepth.
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
            case E::key: {
                Frame& f = frames_.back();
                f.key = parsed.get<std::string>();
                const auto [at, added] = f.seen.try_emplace(f.key, keys_);
                if (!added) throw DuplicateKey{path(), at->second, keys_};
                ++keys_;
                break;
            }
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
        std::map<std::string, size_t> seen;  // keys of this object so far, with their places
    };
    void push(bool isArray) {
        if (frames_.size() >= kMaxDepth) throw TooDeep{path()};
        frames_.push_back({isArray, 0, {}, {}});
    }
    void completeElement() {
        if (!frames_.empty() && frames_.back().isArray) ++frames_.back().count;
    }
    std::vector<Frame> frames_;
    size_t keys_ = 0;  // keys of the whole document so far
};

}  // namespace

Json parseSceneText(const std::string& text, const std::string& source) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw InputError(source, "", "the file is empty; expected a JSON object");
    PathTracker tracker;
    try {
        return Json::parse(text, std::ref(tracker));
    } catch (const DuplicateKey& d) {
        const int a = lineOfKey(text, d.first), b = lineOfKey(text, d.second);
        throw InputError(source, d.path,
                         "the key appears twice in one object (" +
                             (a == b ? "both on line " + std::to_string(a)
                                     : "lines " + std::to_string(a) + " and " + std::to_string(b)) +
                             "); the later would silently replace the earlier");
    } catch (const TooDeep& d) {
        throw InputError(source, d.path,
                         "nested deeper than " + std::to_string(kMaxDepth) + " arrays and objects");
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
