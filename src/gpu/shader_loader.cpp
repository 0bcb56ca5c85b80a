#include "gpu/shader_loader.h"

#include <GL/glew.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "gpu/gpu_options.h"
#include "model/errors.h"

namespace cloth {
namespace fs = std::filesystem;
namespace {

// `#line` directives put the file number into the line number as well as into the source-string
// argument: Mesa (22.x) accepts the argument but prints 0 in its logs. Files stay below this
// many lines.
constexpr int kLineStride = 10000;
constexpr int kMaxIncludeDepth = 16;

std::string lineDirective(int line, int file) {
    return "#line " + std::to_string(file * kLineStride + line) + " " + std::to_string(file) + "\n";
}

// A conditional the loader evaluated (#ifdef/#ifndef) or handed to GLSL (#if).
struct Conditional {
    bool evaluated;
    bool parentActive;
    bool active;  // lines in the current branch are kept
    bool elseSeen = false;
};

class Assembler {
public:
    Assembler(std::string dir, const Defines& defines) : dir_(std::move(dir)) {
        for (const auto& d : defines) defined_.insert(d.first);
    }
    void include(const fs::path& path, const std::string& from, int depth);
    ShaderSource result;

private:
    bool processLine(const std::string& line, const std::string& where, const fs::path& path,
                     int depth, std::vector<Conditional>& stack);

    std::string dir_;
    std::set<std::string> defined_;
    std::set<fs::path> seen_;
};

std::string readFile(const fs::path& path, const std::string& from) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(from + "cannot open shader file " + path.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Splits "#  word rest" into word and rest; empty word if the line is no directive.
std::pair<std::string, std::string> splitDirective(const std::string& line) {
    static const std::regex re(R"(^\s*#\s*(\w+)\s*(.*?)\s*$)");
    std::smatch m;
    if (!std::regex_match(line, m, re)) return {};
    return {m[1].str(), m[2].str()};
}

std::string firstWord(const std::string& s) {
    std::istringstream in(s);
    std::string w;
    in >> w;
    return w.substr(0, w.find('('));
}

void Assembler::include(const fs::path& path, const std::string& from, int depth) {
    if (depth > kMaxIncludeDepth)
        throw std::runtime_error(from + "#include nested too deeply (a cycle?)");
    const fs::path canonical = fs::weakly_canonical(path);
    if (!seen_.insert(canonical).second) return;  // each file once: no include guards needed
    const std::string text = readFile(path, from);
    const int file = int(result.files.size());
    result.files.push_back(path.string());
    result.text += lineDirective(1, file);
    std::vector<Conditional> stack;
    std::istringstream in(text);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where = path.string() + ":" + std::to_string(number) + ": ";
        if (processLine(line, where, path, depth, stack))
            result.text += lineDirective(number + 1, file);
    }
    if (!stack.empty()) throw std::runtime_error(path.string() + ": unterminated #if/#ifdef");
}

// Copies one line, or a blank one where it is inactive, and handles the directives the loader
// owns. Returns true when it wrote an included file instead, so the caller re-synchronises the
// line number.
bool Assembler::processLine(const std::string& line, const std::string& where, const fs::path& path,
                            int depth, std::vector<Conditional>& stack) {
    const auto [word, rest] = splitDirective(line);
    const bool active = stack.empty() || stack.back().active;
    std::string& out = result.text;
    auto keep = [&](bool k) { out += (k ? line : std::string()) + "\n"; };
    if (word == "ifdef" || word == "ifndef") {
        const bool isDefined = defined_.count(firstWord(rest)) > 0;
        stack.push_back({true, active, active && (isDefined == (word == "ifdef"))});
        keep(false);
    } else if (word == "if") {
        stack.push_back({false, active, active});
        keep(active);
    } else if (word == "else" || word == "elif" || word == "endif") {
        if (stack.empty()) throw std::runtime_error(where + "#" + word + " without #if");
        Conditional& c = stack.back();
        if (c.evaluated && word == "elif")
            throw std::runtime_error(where + "#elif after #ifdef/#ifndef is not supported");
        if (c.evaluated && word == "else") {
            if (c.elseSeen) throw std::runtime_error(where + "second #else");
            c.elseSeen = true;
            c.active = c.parentActive && !c.active;
        }
        keep(!c.evaluated && c.parentActive);
        if (word == "endif") stack.pop_back();
    } else if (word == "include" && active) {
        static const std::regex quoted(R"re(^"([^"]+)"$)re");
        std::smatch m;
        if (!std::regex_match(rest, m, quoted))
            throw std::runtime_error(where + "expected #include \"file\"");
        include(path.parent_path() / m[1].str(), where, depth + 1);
        return true;
    } else {
        if (active && word == "define") defined_.insert(firstWord(rest));
        if (active && word == "undef") defined_.erase(firstWord(rest));
        keep(active);
    }
    return false;
}

std::string programLog(GLuint object, bool isProgram) {
    GLint length = 0;
    isProgram ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
              : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    isProgram ? glGetProgramInfoLog(object, length, nullptr, log.data())
              : glGetShaderInfoLog(object, length, nullptr, log.data());
    return log.c_str();
}

GpuSetup& setup() {
    static GpuSetup s;
    return s;
}

}  // namespace

void configureGpu(const GpuSetup& s) {
    setup() = s;
}

const GpuSetup& gpuSetup() {
    return setup();
}

ShaderDirectory findShaderDirectory() {
    if (!gpuSetup().shaderDir.empty())
        return {gpuSetup().shaderDir, "as configured (CLOTH_SHADER_DIR)"};
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && fs::exists(exe.parent_path() / "shaders" / "compute", ec))
        return {(exe.parent_path() / "shaders").string(), "next to the executable"};
#ifdef CLOTH_SOURCE_SHADER_DIR
    return {CLOTH_SOURCE_SHADER_DIR, "the source tree's (none next to the executable)"};
#else
    return {"shaders", "the working directory's"};
#endif
}

int storageBlockCount(const ShaderSource& source) {
    static const std::regex block(
        R"(\blayout\s*\([^)]*\bstd430\b[^)]*\)[^;{}]*\bbuffer\s+\w+\s*\{)");
    const auto begin = std::sregex_iterator(source.text.begin(), source.text.end(), block);
    return int(std::distance(begin, std::sregex_iterator()));
}

void checkStorageBlocks(const ShaderSource& source, int limit) {
    const int needed = storageBlockCount(source);
    if (limit <= 0 || needed <= limit) return;
    throw GpuUnavailable(source.name + " needs " + std::to_string(needed) +
                         " shader storage blocks; this device allows " + std::to_string(limit) +
                         " per compute shader (GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS): choose "
                         "another integrator.method or --backend cpu");
}

ShaderSource assembleShader(const std::string& dir, const std::string& file, const Defines& defines,
                            int glslVersion) {
    const fs::path path = fs::path(dir) / file;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw std::runtime_error("shader file " + path.string() + " not found (shader directory " +
                                 dir + "; set CLOTH_SHADER_DIR to the project's shaders/)");
    Assembler a(dir, defines);
    a.result.name = file;
    a.result.files.push_back("<defines for " + file + ">");
    a.result.text = "#version " + std::to_string(glslVersion) + "\n";
    for (const auto& [name, value] : defines)
        a.result.text += "#define " + name + (value.empty() ? "" : " " + value) + "\n";
    a.include(path, "", 0);
    return a.result;
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex re(R"(^((?:ERROR|WARNING): )?(\d+)[:(](\d+)\)?(.*)$)");
    std::istringstream in(log);
    std::string line, out;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_match(line, m, re)) {
            long source = std::stol(m[2].str()), number = std::stol(m[3].str());
            if (number >= kLineStride) source = number / kLineStride;
            number %= kLineStride;
            if (source >= 0 && source < long(files.size()))
                line = m[1].str() + files[std::size_t(source)] + ":" + std::to_string(number) +
                       m[4].str();
        }
        out += line + "\n";
    }
    return out;
}

unsigned compileComputeProgram(const ShaderSource& source) {
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = mapShaderLog(programLog(shader, false), source.files);
        glDeleteShader(shader);
        throw std::runtime_error("compiling " + source.name + " failed:\n" + log);
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);  // flagged; freed with the program
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = mapShaderLog(programLog(program, true), source.files);
        glDeleteProgram(program);
        throw std::runtime_error("linking " + source.name + " failed:\n" + log);
    }
    return program;
}

}  // namespace cloth
