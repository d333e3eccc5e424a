#pragma once
/// @file
/// Keeps Mesa's software renderer (llvmpipe) working in a process that also holds another
/// copy of LLVM in its global symbol scope.
///
/// Debian 13's libtorch (2.6) links LLVM 19 statically and exports its C functions. In a
/// program linked with libtorch (upkie-rl), libtorch comes before any library opened later
/// in the global scope, so when Mesa (loaded by libEGL at run time) calls
/// LLVMInitializeX86Target and the like, the dynamic linker binds those calls to libtorch's
/// copy of LLVM: the targets are registered there, the system's libLLVM that llvmpipe
/// compiles its shaders with has none, and eglCreateContext dies with a null pointer in
/// libgallium. (Python loads libtorch with RTLD_LOCAL, so the module does not see this.)

namespace upkie_rl {

/// For each libLLVM loaded in the process, calls its own target initializers (x86-64,
/// AArch64, AMDGPU: the native targets and radeonsi's) where the global scope resolves that
/// initializer to another library, that is where Mesa's calls would miss it. Idempotent
/// (LLVM registers a target once), and does nothing where no other library exports LLVM's
/// initializers (Debian 12, the Python module). Call it after libEGL loaded Mesa (the first
/// eglGetPlatformDisplayEXT) and before eglInitialize.
/// @return the number of initializers it called (0 where nothing was shadowed).
int register_shadowed_llvm_targets();

}  // namespace upkie_rl
