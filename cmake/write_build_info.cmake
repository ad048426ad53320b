# Writes generated/build_info.hpp at every build (not only at configure time), so that the commit a
# checkpoint's provenance names is the one the program was built from; "-dirty" when tracked files
# differ from that commit. configure_file rewrites the header only when its text changes, so an
# unchanged commit recompiles nothing. Called by the build_info target of CMakeLists.txt with
# -DSOURCE_DIR, -DTEMPLATE, -DOUTPUT, -DPROJECT_VERSION, -DCOMPILER, -DFLAGS.
execute_process(COMMAND git rev-parse --short=12 HEAD
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE TIDALCRUST_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET
  RESULT_VARIABLE rev_parse)
if(NOT rev_parse EQUAL 0 OR NOT TIDALCRUST_GIT_COMMIT)
  set(TIDALCRUST_GIT_COMMIT "unknown")
else()
  execute_process(COMMAND git diff --quiet HEAD --
    WORKING_DIRECTORY ${SOURCE_DIR} RESULT_VARIABLE dirty ERROR_QUIET)
  if(NOT dirty EQUAL 0)
    string(APPEND TIDALCRUST_GIT_COMMIT "-dirty")
  endif()
endif()
set(TIDALCRUST_COMPILER "${COMPILER}")
set(TIDALCRUST_FLAGS_STRING "${FLAGS}")
configure_file(${TEMPLATE} ${OUTPUT} @ONLY)
