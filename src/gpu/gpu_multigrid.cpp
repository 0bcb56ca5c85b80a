#include "gpu/gpu_multigrid.h"

#include <GL/glew.h>

namespace cloth {
namespace {

// multigrid.glsl's bindings and uniform locations.
constexpr unsigned kStencilBinding = 4, kWorkBinding = 14;
constexpr int kLevelLocation = 4, kLineLocation = 5;
constexpr int kLineGroup = 64;  // mg_lines.comp: a line an invocation

void allocate(unsigned buffer, long long bytes) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_COPY);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32F, GL_RED, GL_FLOAT, nullptr);
}

void run(unsigned program, GLuint x, GLuint y) {
    glUseProgram(program);
    glDispatchCompute(x, y, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace

GpuMultigrid::GpuMultigrid(int nu, int nv, WorkGroup wg, int chunks)
    : levels_(multigridLevels(nu, nv)),
      wg_(wg),
      chunks_(chunks),
      bytes_(multigridBytes(nu, nv, chunks)) {
    glGenBuffers(1, &stencil_);
    glGenBuffers(1, &work_);
    allocate(stencil_, bytes_.stencil);
    allocate(work_, bytes_.work);
}

GpuMultigrid::~GpuMultigrid() {
    glDeleteBuffers(1, &stencil_);
    glDeleteBuffers(1, &work_);
}

void GpuMultigrid::bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kStencilBinding, stencil_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWorkBinding, work_);
}

void GpuMultigrid::dispatchLevel(unsigned program, int level) const {
    const MultigridLevel& l = levels_[std::size_t(level)];
    glProgramUniform1i(program, kLevelLocation, level);
    run(program, GLuint((l.nu + wg_.x - 1) / wg_.x), GLuint((l.nv + wg_.y - 1) / wg_.y));
}

void GpuMultigrid::dispatchLines(unsigned program, int level, int count) const {
    if (count <= 0) return;
    glProgramUniform1i(program, kLevelLocation, level);
    run(program, GLuint((count + kLineGroup - 1) / kLineGroup), 1);
}

void GpuMultigrid::dispatchChunks(unsigned program, int level, int lines, int perGroup) const {
    if (lines <= 0) return;
    glProgramUniform1i(program, kLevelLocation, level);
    run(program, GLuint((lines + perGroup - 1) / perGroup), 1);
}

void GpuMultigrid::linearise(const Programs& programs) const {
    const int last = levels() - 1;
    for (int l = 0; l < levels(); ++l) {
        if (l == 0)
            dispatchLevel(programs[int(Kernel::MgFine)], 0);
        else
            dispatchLevel(programs[int(Kernel::MgGalerkin)], l);
        // The coarsest grid is solved by its dense factor, not relaxed.
        if (l < last) {
            const int lines = levels_[std::size_t(l)].nu + levels_[std::size_t(l)].nv;
            dispatchLines(programs[int(Kernel::MgLines)], l, lines);
            if (chunks_ > 1) dispatchChunks(programs[int(Kernel::MgLineTransfers)], l, lines, 1);
        }
    }
    run(programs[int(Kernel::MgCoarsestFactor)], 1, 1);
}

void GpuMultigrid::apply(const Programs& programs) const {
    dispatchLevel(programs[int(Kernel::MgBegin)], 0);
    cycle(programs, 0);
}

// One direction's 5 colours of lines, in turn (backwards for the adjoint sweep): each colour's
// right-hand sides a vertex an invocation (x along the line, y the colour's lines), then its
// lines solved.
void GpuMultigrid::sweep(const Programs& programs, int level, int direction, bool forward) const {
    const unsigned rightHandSide = programs[int(Kernel::MgRelaxRightHandSide)];
    const unsigned solve = programs[int(Kernel::MgRelax)];
    const MultigridLevel& l = levels_[std::size_t(level)];
    const int lines = direction == 0 ? l.nv : l.nu, length = direction == 0 ? l.nu : l.nv;
    for (int c = 0; c < 5; ++c) {
        const int colour = forward ? c : 4 - c;
        const int count = (lines - colour + 4) / 5;  // lines colour, colour + 5, …
        if (count <= 0) continue;
        // multigrid.glsl uLine: level, direction and colour in one uniform.
        const int line = 16 * level + 8 * direction + colour;
        for (unsigned program : {rightHandSide, solve})
            glProgramUniform1i(program, kLineLocation, line);
        run(rightHandSide, GLuint((length + wg_.x - 1) / wg_.x),
            GLuint((count + wg_.y - 1) / wg_.y));
        const int perGroup = multigridRelaxGroup(chunks_) / chunks_;
        run(solve, GLuint((count + perGroup - 1) / perGroup), 1);
    }
}

// z = V r on `level` (cpu/cpu_multigrid.cpp cycle): z starts at 0 (mg_begin, mg_restrict).
void GpuMultigrid::cycle(const Programs& programs, int level) const {
    if (level + 1 == levels()) {
        run(programs[int(Kernel::MgCoarsestSolve)], 1, 1);
        return;
    }
    sweep(programs, level, 0, true);  // rows, then columns
    sweep(programs, level, 1, true);
    dispatchLevel(programs[int(Kernel::MgResidual)], level);
    dispatchLevel(programs[int(Kernel::MgRestrict)], level + 1);
    cycle(programs, level + 1);
    dispatchLevel(programs[int(Kernel::MgProlong)], level);
    sweep(programs, level, 1, false);  // the adjoint: columns, then rows, colours reversed
    sweep(programs, level, 0, false);
}

}  // namespace cloth
