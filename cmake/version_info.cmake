# Writes OUTPUT (experiments/version_info.cpp.in filled in) with the project's version, the
# source tree's commit (with "-modified" when tracked files outside results/ and plots/
# differ from it; "unknown" outside a git checkout) and the build's flavour, rewriting it only
# when one of them changed, so that an unchanged tree rebuilds nothing.
# Run at every build: cmake -DSOURCE_DIR=... -DOUTPUT=... -DVERSION=... -DFLAVOUR=... -P this
set(RADQUAD_COMMIT unknown)
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse HEAD
                  OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET
                  RESULT_VARIABLE status)
  string(LENGTH "${head}" length)
  if(status EQUAL 0 AND length EQUAL 40)
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} status --porcelain
                            --untracked-files=no -- . :!results :!plots
                    OUTPUT_VARIABLE changes ERROR_QUIET)
    set(RADQUAD_COMMIT ${head})
    if(NOT changes STREQUAL "")
      string(APPEND RADQUAD_COMMIT "-modified")
    endif()
  endif()
endif()
set(RADQUAD_VERSION ${VERSION})
set(RADQUAD_BUILD_FLAVOUR ${FLAVOUR})
configure_file(${SOURCE_DIR}/experiments/version_info.cpp.in ${OUTPUT} @ONLY)
