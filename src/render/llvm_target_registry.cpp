#include "render/llvm_target_registry.hpp"

#include <dlfcn.h>
#include <link.h>

#include <cstring>
#include <string>
#include <vector>

namespace upkie_rl {

namespace {

// The targets Mesa's LLVM drivers initialize: the host's (llvmpipe) and AMDGPU (radeonsi).
constexpr const char* kTargets[] = {"X86", "AArch64", "AMDGPU"};
constexpr const char* kTargetParts[] = {"TargetInfo", "Target",    "TargetMC",
                                        "AsmPrinter", "AsmParser", "Disassembler"};

int collect_llvm_paths(dl_phdr_info* info, std::size_t /*size*/, void* paths) {
  const char* name = info->dlpi_name;
  if (name != nullptr && std::strstr(name, "/libLLVM") != nullptr) {
    static_cast<std::vector<std::string>*>(paths)->emplace_back(name);
  }
  return 0;
}

// Calls `library`'s own initializers that the global scope resolves to another library (none
// there: Mesa's calls reach `library`'s own, nothing to do).
int register_targets_of(void* library) {
  int called = 0;
  for (const char* target : kTargets) {
    for (const char* part : kTargetParts) {
      const std::string name = std::string("LLVMInitialize") + target + part;
      void* own = dlsym(library, name.c_str());
      void* global = dlsym(RTLD_DEFAULT, name.c_str());
      if (own == nullptr || global == nullptr || global == own) continue;
      reinterpret_cast<void (*)()>(own)();
      ++called;
    }
  }
  return called;
}

}  // namespace

int register_shadowed_llvm_targets() {
  std::vector<std::string> paths;
  dl_iterate_phdr(collect_llvm_paths, &paths);
  int called = 0;
  for (const std::string& path : paths) {
    // RTLD_NOLOAD: a handle on the copy already loaded (Mesa's), never a new one.
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
    if (library == nullptr) continue;
    called += register_targets_of(library);
    dlclose(library);
  }
  return called;
}

}  // namespace upkie_rl
