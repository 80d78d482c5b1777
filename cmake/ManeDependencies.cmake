# Every dependency comes from a Debian 12 package; scripts/install-deps.sh installs them.
# Each part looks only for what it uses, so a physics-only build (-DMANE_COMPONENTS=physics,
# cmake/ManeComponents.cmake) asks for GLM and nothing else.

find_package(Threads REQUIRED)
find_package(glm CONFIG REQUIRED)

if("subdiv" IN_LIST MANE_COMPONENTS)
  # OpenSubdiv: Debian's CMake package is broken (it expects libosdCPU.a, which libosd-dev does
  # not ship), so build our own imported target from the header and the shared library.
  find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
  find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
  add_library(mane_opensubdiv INTERFACE)
  target_include_directories(mane_opensubdiv SYSTEM INTERFACE "${OPENSUBDIV_INCLUDE_DIR}")
  target_link_libraries(mane_opensubdiv INTERFACE "${OPENSUBDIV_CPU_LIBRARY}")
endif()

if("render" IN_LIST MANE_COMPONENTS)
  find_package(Vulkan REQUIRED)
  find_package(OpenEXR CONFIG REQUIRED)
  find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

  # stb: Debian builds the implementations into libstb; the headers live under stb/.
  find_path(STB_INCLUDE_DIR stb/stb_image.h REQUIRED)
  find_library(STB_LIBRARY stb REQUIRED)
  add_library(mane_stb INTERFACE)
  target_include_directories(mane_stb SYSTEM INTERFACE "${STB_INCLUDE_DIR}/stb")
  target_link_libraries(mane_stb INTERFACE "${STB_LIBRARY}")
endif()

if("scene" IN_LIST MANE_COMPONENTS)
  find_package(TinyGLTF CONFIG REQUIRED)
  find_package(tinyobjloader CONFIG REQUIRED)
  find_package(nlohmann_json CONFIG REQUIRED)
  find_package(OpenSSL REQUIRED COMPONENTS Crypto)
  find_package(CURL REQUIRED)
  find_package(meshoptimizer CONFIG REQUIRED)
endif()

# The window (mane_window, `mane view`) is the program's alone.
if(MANE_BUILD_APP)
  find_package(glfw3 CONFIG REQUIRED)
endif()

if(MANE_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
  include(GoogleTest)
endif()
if(MANE_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
