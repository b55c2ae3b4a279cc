# `cmake --install BUILD [--prefix DIR]`: the radquad command, the libraries with their
# headers, exported CMake targets (find_package(radquad) gives radquad::kernel,
# radquad::quadrature, radquad::radiosity, radquad::trace, radquad::reference and
# radquad::experiments), a pkg-config file (radquad.pc), the study configs and plot scripts
# the commands read (share/radquad), and the Python module when it is built. The installed
# tree is relocatable: the command finds share/radquad next to its own bin/ folder
# (experiments/study/study_output.h, dataRoot), and the CMake package is found relative to
# its own folder. The libraries are static; their Debian dependencies are found again by
# the package's config file.

# Compiled with -march=native (RADQUAD_NATIVE), the libraries' Eigen types are laid out for
# this CPU's vectors, so a program using them must be compiled the same way.
target_compile_features(radquad_kernel PUBLIC cxx_std_20)
if(RADQUAD_NATIVE)
  target_compile_options(radquad_kernel INTERFACE $<INSTALL_INTERFACE:-march=native>)
endif()

set(RADQUAD_LIBRARIES radquad_kernel radquad_quadrature radquad_radiosity radquad_trace
    radquad_reference radquad_experiments)
set_target_properties(radquad_kernel PROPERTIES EXPORT_NAME kernel)
set_target_properties(radquad_quadrature PROPERTIES EXPORT_NAME quadrature)
set_target_properties(radquad_radiosity PROPERTIES EXPORT_NAME radiosity)
set_target_properties(radquad_trace PROPERTIES EXPORT_NAME trace)
set_target_properties(radquad_reference PROPERTIES EXPORT_NAME reference)
set_target_properties(radquad_experiments PROPERTIES EXPORT_NAME experiments)

install(TARGETS radquad ${RADQUAD_LIBRARIES}
  EXPORT radquadTargets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(folder kernel quadrature radiosity reference experiments)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/radquad/${folder}
    FILES_MATCHING PATTERN "*.h")
endforeach()

set(RADQUAD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/radquad)
install(EXPORT radquadTargets NAMESPACE radquad:: DESTINATION ${RADQUAD_CMAKE_DIR})
include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/radquadConfig.cmake.in
  ${PROJECT_BINARY_DIR}/radquadConfig.cmake INSTALL_DESTINATION ${RADQUAD_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/radquadConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/radquadConfig.cmake
  ${PROJECT_BINARY_DIR}/radquadConfigVersion.cmake DESTINATION ${RADQUAD_CMAKE_DIR})

# pkg-config: the static libraries in dependency order, then what they need (Embree 3 and
# libcubature have no pkg-config file on Debian).
if(RADQUAD_NATIVE)
  set(RADQUAD_PC_CFLAGS "-march=native")
else()
  set(RADQUAD_PC_CFLAGS "")
endif()
file(RELATIVE_PATH RADQUAD_PC_PREFIX /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
configure_file(${PROJECT_SOURCE_DIR}/cmake/radquad.pc.in ${PROJECT_BINARY_DIR}/radquad.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/radquad.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# What the commands read: the study configs (`radquad figures`) and the plot scripts.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/experiments/configs
  DESTINATION ${CMAKE_INSTALL_DATADIR}/radquad/experiments)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/plots/ DESTINATION ${CMAKE_INSTALL_DATADIR}/radquad/plots
  FILES_MATCHING PATTERN "*.py")
