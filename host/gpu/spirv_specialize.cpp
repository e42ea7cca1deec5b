// spirv_specialize.cpp: spirv_specialize.h, by SPIRV-Tools' optimizer (Debian's
// spirv-tools, linked statically: libSPIRV-Tools-opt.a).
#include "gpu/spirv_specialize.h"

#include <cstdlib>
#include <cstring>
#include <spirv-tools/optimizer.hpp>
#include <unordered_map>
#include <vector>

extern "C" bool rc_spirv_specialize(rc_spirv module, const uint32_t *values, uint32_t count, rc_spirv *out) {
  try {
    std::unordered_map<uint32_t, std::vector<uint32_t>> bits;
    for (uint32_t id = 0; id < count; id++) bits[id] = {values[id]};
    spvtools::Optimizer opt(SPV_ENV_VULKAN_1_1);
    // Set each constant's default to its value, make it an OpConstant, fold the
    // OpSpecConstantOp expressions and composites (gl_WorkGroupSize) built on them; then
    // drop the branches those decide, the functions nothing calls any more, and the code
    // whose results nothing uses. Bindings and the interface stay as they are: the pipeline
    // layout is the same for both modules. Then the function-local variables become SSA
    // values (the memory-to-register passes of spirv-opt -O, without its inlining, which
    // made the module larger and lavapipe slower; RC_SPIRV_SPECIALIZE_PASSES names this list).
    opt.RegisterPass(spvtools::CreateSetSpecConstantDefaultValuePass(bits))
        .RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass(true))
        .RegisterPass(spvtools::CreatePrivateToLocalPass())
        .RegisterPass(spvtools::CreateLocalSingleBlockLoadStoreElimPass())
        .RegisterPass(spvtools::CreateLocalSingleStoreElimPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass(true))
        .RegisterPass(spvtools::CreateScalarReplacementPass(100))
        .RegisterPass(spvtools::CreateLocalAccessChainConvertPass())
        .RegisterPass(spvtools::CreateLocalSingleBlockLoadStoreElimPass())
        .RegisterPass(spvtools::CreateLocalSingleStoreElimPass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass(true))
        .RegisterPass(spvtools::CreateSSARewritePass())
        .RegisterPass(spvtools::CreateAggressiveDCEPass(true));
    // The input is the build's own module, which spirv-val checks in the test suite; the
    // output is validated by the validation layer wherever that runs.
    spvtools::OptimizerOptions options;
    options.set_run_validator(false);
    std::vector<uint32_t> words;
    if (!opt.Run(module.words, module.size / sizeof(uint32_t), &words, options) || words.empty()) return false;
    uint32_t *copy = static_cast<uint32_t *>(std::malloc(words.size() * sizeof(uint32_t)));
    if (!copy) return false;
    std::memcpy(copy, words.data(), words.size() * sizeof(uint32_t));
    out->words = copy;
    out->size = words.size() * sizeof(uint32_t);
    return true;
  } catch (...) {  // std::bad_alloc inside the optimizer: the driver specializes instead
    return false;
  }
}
