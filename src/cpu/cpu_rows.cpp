#include "cpu/cpu_rows.h"

#include <stdexcept>
#include <string>

#include "model/errors.h"

namespace cloth {

const char* cpuIsaName(CpuIsa isa) {
    switch (isa) {
        case CpuIsa::Auto:
            return "auto";
        case CpuIsa::Scalar:
            return "scalar";
        case CpuIsa::Generic:
            return "generic";
        case CpuIsa::Avx2:
            return "avx2";
        case CpuIsa::Avx512:
            return "avx512";
    }
    return "?";
}

bool cpuIsaSupported(CpuIsa isa) {
#if defined(__x86_64__) || defined(__i386__)
    switch (isa) {
        case CpuIsa::Avx2:
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
        case CpuIsa::Avx512:
            return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                   __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
        default:
            return true;
    }
#else
    return isa != CpuIsa::Avx2 && isa != CpuIsa::Avx512;
#endif
}

std::optional<CpuIsa> cpuIsaFromName(const std::string& name) {
    for (CpuIsa isa : {CpuIsa::Auto, CpuIsa::Scalar, CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512})
        if (name == cpuIsaName(isa)) return isa;
    return std::nullopt;
}

CpuIsa resolveCpuIsa(CpuIsa requested) {
    if (requested == CpuIsa::Auto) {
        for (CpuIsa isa : {CpuIsa::Avx512, CpuIsa::Avx2, CpuIsa::Generic})
            if (cpuIsaSupported(isa)) return isa;
    }
    if (!cpuIsaSupported(requested))
        throw InputError(
            "", "CLOTH_CPU_ISA",
            std::string("this CPU lacks the ") + cpuIsaName(requested) + " instructions");
    return requested;
}

template <typename T>
const RowKernels<T>& rowKernels(CpuIsa isa) {
    switch (isa) {
        case CpuIsa::Avx512:
            return isa_avx512::rowKernels<T>();
        case CpuIsa::Avx2:
            return isa_avx2::rowKernels<T>();
        default:
            return isa_generic::rowKernels<T>();
    }
}
template const RowKernels<float>& rowKernels(CpuIsa);
template const RowKernels<double>& rowKernels(CpuIsa);

}  // namespace cloth
