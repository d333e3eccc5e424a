# The browser viewer (web/viewer): the page and its npm packages (three.js, urdf-loader,
# uPlot), installed from package-lock.json by `npm ci` (scripts/install-deps.sh), are
# bundled into viewer.js by web/viewer/build.mjs (esbuild), then compiled into the view
# layer by embed_viewer.cmake. Sets UPKIE_RL_VIEWER_ASSETS, the generated C++ source.
set(VIEWER_SOURCE_DIR ${PROJECT_SOURCE_DIR}/web/viewer)
set(VIEWER_BUILD_DIR ${PROJECT_BINARY_DIR}/viewer)
find_program(NODE_EXECUTABLE node)
if(NOT NODE_EXECUTABLE)
  message(FATAL_ERROR "the viewer needs Node.js: run scripts/install-deps.sh")
endif()
file(GLOB VIEWER_PAGE_SOURCES CONFIGURE_DEPENDS ${VIEWER_SOURCE_DIR}/src/*)

# The npm packages are installed in the source tree by scripts/install-deps.sh (`npm ci`), not
# here: build trees (build/, build-sanitize/, ...) share them, and two `npm ci` at once would
# break each other. build.mjs refuses a package-lock.json newer than the installed packages.
if(NOT EXISTS ${VIEWER_SOURCE_DIR}/node_modules/.package-lock.json)
  message(FATAL_ERROR "the viewer's npm packages are missing: run scripts/install-deps.sh "
                      "(or `npm ci` in web/viewer)")
endif()
add_custom_command(
  OUTPUT ${VIEWER_BUILD_DIR}/viewer.js ${VIEWER_BUILD_DIR}/index.html
  COMMAND ${NODE_EXECUTABLE} ${VIEWER_SOURCE_DIR}/build.mjs ${VIEWER_BUILD_DIR}
  DEPENDS ${VIEWER_PAGE_SOURCES} ${VIEWER_SOURCE_DIR}/build.mjs
          ${VIEWER_SOURCE_DIR}/package-lock.json
  WORKING_DIRECTORY ${VIEWER_SOURCE_DIR}
  COMMENT "Bundling the viewer page (esbuild)")
set(UPKIE_RL_VIEWER_ASSETS ${PROJECT_BINARY_DIR}/generated/viewer_assets.cpp)
add_custom_command(
  OUTPUT ${UPKIE_RL_VIEWER_ASSETS}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/generated
  COMMAND ${CMAKE_COMMAND} -DPAGE=${VIEWER_BUILD_DIR}/index.html
          -DSCRIPT=${VIEWER_BUILD_DIR}/viewer.js -DOUTPUT=${UPKIE_RL_VIEWER_ASSETS}
          -P ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
  DEPENDS ${VIEWER_BUILD_DIR}/viewer.js ${VIEWER_BUILD_DIR}/index.html
          ${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake
  COMMENT "Compiling the viewer page into the view layer")
# ISO C++ only promises 65,536 characters per string literal; GCC and Clang take any length.
set_source_files_properties(${UPKIE_RL_VIEWER_ASSETS} PROPERTIES COMPILE_OPTIONS
  "-Wno-overlength-strings")
