# How the libraries reach other projects: the mane::<name> targets, the installed headers, the
# CMake package (find_package(mane CONFIG COMPONENTS ...)) and the physics' pkg-config file.
#
#   mane_public_library(<target> <name> [EXCLUDE_HEADERS <file names>...])
#       Call in the module's folder. <target> becomes mane::<name> for projects that add mane with
#       add_subdirectory and for those that find an installed mane. Installs the library and every
#       *.hpp of the folder, except detail/ folders and the files named, as
#       include/mane/<folder>/…
#   mane_install_package()
#       Call once, after every module: the helper targets the static libraries link privately,
#       the package files and the pkg-config file.
#
# Headers. Consumers write #include <mane/physics/hair.hpp>. The headers themselves include one
# another as "physics/…" and "common/…", so include/mane is on the include path as well as
# include/: that keeps the installed headers byte for byte the ones in the source tree. In a
# build tree, <build>/include/mane is a link to the source tree, so the <mane/…> spelling works
# there too (add_subdirectory).

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(MANE_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/mane")

file(MAKE_DIRECTORY "${PROJECT_BINARY_DIR}/include")
file(CREATE_LINK "${PROJECT_SOURCE_DIR}" "${PROJECT_BINARY_DIR}/include/mane" SYMBOLIC)

function(mane_public_library target name)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "" "EXCLUDE_HEADERS")
  add_library(mane::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(${target} PUBLIC
    "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>"
    "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>"
    "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/mane>")
  # The public headers use C++23 (std::expected): consumers compile them as C++23 too.
  target_compile_features(${target} PUBLIC cxx_std_23)
  if(NOT MANE_INSTALL)
    return()
  endif()

  install(TARGETS ${target} EXPORT maneTargets
    ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
    RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  file(RELATIVE_PATH folder "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}")
  set(excluded PATTERN detail EXCLUDE PATTERN examples EXCLUDE)
  foreach(file_name IN LISTS arg_EXCLUDE_HEADERS)
    list(APPEND excluded PATTERN "${file_name}" EXCLUDE)
  endforeach()
  # A rule over the folder rather than a list: a header added later is installed without
  # touching this file.
  install(DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}/"
    DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/mane/${folder}"
    FILES_MATCHING PATTERN "*.hpp" ${excluded})
endfunction()

function(mane_install_package)
  if(NOT MANE_INSTALL)
    return()
  endif()

  # The libraries are static, so an installed one names its private dependencies too: the
  # compile flags (empty at link time; linking mane::determinism compiles your own code the
  # way mane's is), the embedded shaders, and the Debian libraries found by path.
  set(helpers
    mane_warnings warnings
    mane_determinism determinism
    mane_shaders shaders
    mane_stb stb
    mane_opensubdiv opensubdiv)
  while(helpers)
    list(POP_FRONT helpers target name)
    if(TARGET ${target})
      set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
      install(TARGETS ${target} EXPORT maneTargets ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}")
    endif()
  endwhile()

  install(EXPORT maneTargets NAMESPACE mane:: DESTINATION "${MANE_INSTALL_CMAKEDIR}")
  if(TARGET mane)
    install(TARGETS mane RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
  endif()

  configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/maneConfig.cmake.in"
    "${PROJECT_BINARY_DIR}/package/maneConfig.cmake"
    INSTALL_DESTINATION "${MANE_INSTALL_CMAKEDIR}")
  # 0.x: a minor release may change the API, so only the same major.minor is compatible.
  write_basic_package_version_file("${PROJECT_BINARY_DIR}/package/maneConfigVersion.cmake"
    COMPATIBILITY SameMinorVersion)
  install(FILES "${PROJECT_BINARY_DIR}/package/maneConfig.cmake" "${PROJECT_BINARY_DIR}/package/maneConfigVersion.cmake"
    DESTINATION "${MANE_INSTALL_CMAKEDIR}")

  if("physics" IN_LIST MANE_COMPONENTS)
    # pkg-config finds prefix from where the .pc file lies, so the install can be moved.
    if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
      set(MANE_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
    else()
      file(RELATIVE_PATH pc_to_prefix "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
      string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
      set(MANE_PC_PREFIX "\${pcfiledir}/${pc_to_prefix}")
    endif()
    foreach(dir LIBDIR INCLUDEDIR)
      if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
        set(MANE_PC_${dir} "${CMAKE_INSTALL_${dir}}")
      else()
        set(MANE_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
      endif()
    endforeach()
    configure_file("${PROJECT_SOURCE_DIR}/cmake/mane-physics.pc.in" "${PROJECT_BINARY_DIR}/package/mane-physics.pc"
      @ONLY)
    install(FILES "${PROJECT_BINARY_DIR}/package/mane-physics.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
  endif()
endfunction()
