// implicit_euler's multigrid preconditioner on the GPU (docs/integrators.md, "Preconditioners"):
// the V-cycle of cpu/cpu_multigrid.h, pass for pass, in double, in the kernels of
// shaders/compute/mg_*.comp (multigrid.glsl). This class owns the hierarchy's two buffers and
// says which kernels run in what order; GpuSolver owns the programs and the CG around it.
//
// Per step, after the right-hand side (linearise): the fine grid's stencil (mg_fine), each
// coarser grid's Galerkin product (mg_galerkin), every grid's line factors (mg_lines) with their
// chunks' transfers (mg_line_transfers) and the coarsest grid's dense factor. Per application of
// M⁻¹ (apply): the conjugate gradient's r into the fine grid (mg_begin), then on each grid 5
// colours of rows and 5 of columns relaxed (mg_relax_right_hand_side, then mg_relax: a line a
// work group, its substitutions in chunks, an invocation each, rather than the CPU's one chain a
// line), t = r − A z (mg_residual), r_c = Pᵀ t (mg_restrict), the
// coarser grid's cycle, z += P z_c (mg_prolong) and the same sweeps in reverse order; the coarsest
// grid is solved by its factor (mg_coarsest_solve). Nothing leaves the GPU; every kernel of apply
// returns at once once the solve has converged.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "gpu/gpu_variant.h"
#include "model/multigrid_levels.h"

namespace cloth {

class GpuMultigrid {
public:
    using Programs = std::array<unsigned, kKernelCount>;

    // Allocates the buffers for the scene's grid (checkMultigridFits first).
    // `chunks`: the most chunks a line's solve is cut into (multigridChunks).
    GpuMultigrid(int nu, int nv, WorkGroup wg, int chunks);
    ~GpuMultigrid();
    GpuMultigrid(const GpuMultigrid&) = delete;
    GpuMultigrid& operator=(const GpuMultigrid&) = delete;

    void bind() const;  // the buffers at their bindings (multigrid.glsl)
    void linearise(const Programs& programs) const;
    void apply(const Programs& programs) const;
    std::size_t bytes() const { return std::size_t(bytes_.stencil + bytes_.work); }
    // Each level's stencil diagonal, line factors' pivots, |r| and |z|, and what is not finite,
    // read back (gpu_multigrid_trace.cpp): for CLOTH_MULTIGRID_TRACE.
    std::string describe() const;
    int levels() const { return int(levels_.size()); }

private:
    void dispatchLevel(unsigned program, int level) const;             // 2-D over the level's grid
    void dispatchLines(unsigned program, int level, int count) const;  // 1-D, 64 a group
    // mg_line_transfers (a group a line) or mg_relax (multigridRelaxGroup) over `lines` lines.
    void dispatchChunks(unsigned program, int level, int lines, int perGroup) const;
    void sweep(const Programs& programs, int level, int direction, bool forward) const;
    void cycle(const Programs& programs, int level) const;

    std::vector<MultigridLevel> levels_;
    WorkGroup wg_;
    int chunks_;
    MultigridBytes bytes_;
    unsigned stencil_ = 0, work_ = 0;
};

}  // namespace cloth
