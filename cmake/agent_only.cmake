# UPKIE_RL_AGENT_ONLY: only the robot runner, upkie-rl-agent, from the runner's sources
# (base, the engine-free cores of model, sim, spine, envs, vec and policy, then agent), for the
# robot's aarch64 computer (`make pi`, with cmake/aarch64-linux-gnu.cmake).
#
# The header-only dependencies (Eigen, nlohmann-json, msgpack-cxx, CLI11, spdlog and fmt,
# both header-only here) come from this machine's Debian -dev packages, whose headers do not
# depend on the architecture; they are staged in one folder so that the host's other headers
# (its C library's) stay out of the cross compiler's way. The four compiled libraries the
# runner needs (yaml-cpp, urdfdom's model, TinyXML, console_bridge) are Debian's arm64
# packages, installed through multiarch (scripts/install-deps.sh); the bundle carries them.

set(UPKIE_RL_ARM64_LIBDIR /usr/lib/aarch64-linux-gnu CACHE PATH "Debian's arm64 libraries")
set(staged ${PROJECT_BINARY_DIR}/staged-include)
file(MAKE_DIRECTORY ${staged})
# Debian 13 moved urdfdom's headers one folder down (urdfdom/, urdfdom_headers/).
foreach(header eigen3 nlohmann msgpack msgpack.hpp spdlog fmt CLI yaml-cpp urdf_model
        urdf_model_state urdf_world urdf_sensor urdf_exception urdf_parser console_bridge
        console_bridge_export.h tinyxml.h)
  if(NOT EXISTS ${staged}/${header})
    foreach(folder /usr/include /usr/include/urdfdom /usr/include/urdfdom_headers)
      if(EXISTS ${folder}/${header})
        file(CREATE_LINK ${folder}/${header} ${staged}/${header} SYMBOLIC)
        break()
      endif()
    endforeach()
    if(NOT EXISTS ${staged}/${header})
      message(FATAL_ERROR "/usr/include/${header} is missing: run scripts/install-deps.sh")
    endif()
  endif()
endforeach()

# `pattern`: the library's soname, with a wildcard where Debian releases differ.
function(upkie_rl_arm64_library target pattern)
  file(GLOB file ${UPKIE_RL_ARM64_LIBDIR}/${pattern})
  if(NOT file)
    message(FATAL_ERROR "${UPKIE_RL_ARM64_LIBDIR}/${pattern} is missing: run scripts/install-deps.sh")
  endif()
  list(GET file 0 file)
  add_library(${target} SHARED IMPORTED)
  set_target_properties(${target} PROPERTIES IMPORTED_LOCATION ${file})
endfunction()
# yaml-cpp 0.7 and urdfdom 3 on Debian 12, 0.8 and 4 on Debian 13.
upkie_rl_arm64_library(yaml-cpp libyaml-cpp.so.0.[0-9])
upkie_rl_arm64_library(urdfdom_model liburdfdom_model.so.[0-9].0)
upkie_rl_arm64_library(tinyxml libtinyxml.so.2.6.2)
upkie_rl_arm64_library(console_bridge libconsole_bridge.so.1.0)
find_package(Threads REQUIRED)

add_library(upkie_rl_pi_headers INTERFACE)
target_include_directories(upkie_rl_pi_headers SYSTEM INTERFACE ${staged} ${staged}/eigen3)
# spdlog and fmt without their compiled libraries; msgpack-cxx without Boost.
target_compile_definitions(upkie_rl_pi_headers INTERFACE SPDLOG_HEADER_ONLY FMT_HEADER_ONLY
  MSGPACK_NO_BOOST MSGPACK_DEFAULT_API_VERSION=3)

set(agent_sources "")
foreach(layer base model sim spine envs vec policy agent)
  file(GLOB_RECURSE layer_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${layer}/*.cpp)
  list(APPEND agent_sources ${layer_sources})
endforeach()
foreach(source ${UPKIE_RL_ENGINE_SOURCES})
  list(REMOVE_ITEM agent_sources ${PROJECT_SOURCE_DIR}/src/${source})
endforeach()
add_library(upkie_rl_agent_pi STATIC ${agent_sources})
target_include_directories(upkie_rl_agent_pi PUBLIC ${PROJECT_SOURCE_DIR}/src)
target_compile_definitions(upkie_rl_agent_pi PUBLIC
  UPKIE_RL_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
  UPKIE_RL_MODEL_PATH="upkie.urdf")
# The version and commit of --version (the top-level CMakeLists.txt's upkie_rl_build_info).
target_sources(upkie_rl_agent_pi PRIVATE ${UPKIE_RL_BUILD_INFO})
add_dependencies(upkie_rl_agent_pi upkie_rl_build_info)
target_link_libraries(upkie_rl_agent_pi PUBLIC upkie_rl_pi_headers yaml-cpp urdfdom_model tinyxml
  console_bridge Threads::Threads rt)

add_executable(upkie-rl-agent ${PROJECT_SOURCE_DIR}/src/apps/agent_main.cpp
  ${PROJECT_SOURCE_DIR}/src/cli/interrupt_handlers.cpp)
target_link_libraries(upkie-rl-agent PRIVATE upkie_rl_agent_pi)
# The bundle's lib/ holds the four arm64 libraries and the C++ runtime they share with it.
set_target_properties(upkie-rl-agent PROPERTIES BUILD_RPATH "$ORIGIN/lib" INSTALL_RPATH "$ORIGIN/lib")
