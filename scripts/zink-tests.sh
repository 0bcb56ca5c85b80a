#!/usr/bin/env bash
# Runs a set of the GPU tests on a second OpenGL implementation: Mesa's zink (OpenGL over Vulkan)
# on lavapipe, both on the CPU, where the other GPU tests run on llvmpipe. Its compiler path
# (GLSL to SPIR-V to lavapipe) is not llvmpipe's: with it the multigrid smoother once ran with
# the uniforms of an earlier dispatch (docs/gpu.md "Drivers"). Fails when zink is not what
# renders. Usage: zink-tests.sh CLOTHSIM CLOTH_TESTS; needs mesa-vulkan-drivers.
set -euo pipefail
exe=${1:?clothsim}
tests=${2:?cloth_tests}

export MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1 CLOTH_REQUIRE_GPU=1
XDG_RUNTIME_DIR=$(mktemp -d)  # zink's loader asks for one (mode 0700)
export XDG_RUNTIME_DIR
trap 'rm -rf "$XDG_RUNTIME_DIR"' EXIT

renderer=$("$exe" info 2>/dev/null | sed -n 's/^ *GL renderer: *//p')
case "$renderer" in
zink*) echo "zink-tests.sh: $renderer" ;;
*)
    echo "zink-tests.sh: the GPU backend does not run on zink here (renderer: ${renderer:-none});" \
        "apt-get install mesa-vulkan-drivers" >&2
    exit 1
    ;;
esac

# The multigrid V-cycle against the CPU's (what zink got wrong), then parity on the other paths.
# Not here: the chaotic runs whose outcome the rounding decides (a frictionless tablecloth's
# slide, the drape after its contact), where zink and llvmpipe part like any two devices.
filter='GpuMultigridSolve.EveryTermOfTheSystemMatchesTheCpu'
filter+=':GpuMultigridSolve.TheStiffSheetTakesFewIterationsWhereJacobiTakesHundreds'
filter+=':GpuMultigridSolve.ChunkedLineSolvesGiveTheOneChainVCycle'
filter+=':GpuCpuParity.*:GpuVbdTranslation.ItsLevelsStepTheLandingAsOnTheCpu'
filter+=':GpuColliderSolver.EveryShapeMatchesTheReferenceAndEndsNoStepInside'
# The renderer's shaders: `clothsim render` pictures, and the normals the GPU draws with.
filter+=':RenderCommand.DrapeAtRestShowsClothSphereAndGround:RenderCommand.GpuAndCpuPicturesAgree'
filter+=':RenderCommand.StrainModeColoursAStretchedCloth:GpuNormals.*'
# Mesa's EGL warns on every platform it cannot open before it finds the software device.
"$tests" --gtest_filter="$filter" 2> >(grep -v -e 'failed to create dri2 screen' -e XDG_RUNTIME_DIR >&2)
