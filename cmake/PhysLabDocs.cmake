# `docs` target: the Doxygen site (main page, handouts, conventions, API of common/) with the
# charts the demos wrote into ${PHYSLAB_CHART_DIR}. Warnings in common/ fail the build.
set(PHYSLAB_CHART_DIR "${CMAKE_BINARY_DIR}/charts" CACHE PATH "Where demos write charts for the docs")
find_package(Doxygen QUIET OPTIONAL_COMPONENTS dot)
if(DOXYGEN_FOUND)
  set(PHYSLAB_HAVE_DOT NO)
  if(DOXYGEN_DOT_FOUND)
    set(PHYSLAB_HAVE_DOT YES)
  endif()
  configure_file("${PHYSLAB_ROOT}/docs/Doxyfile.in" "${CMAKE_BINARY_DIR}/Doxyfile" @ONLY)
  add_custom_target(docs
    COMMAND "${DOXYGEN_EXECUTABLE}" "${CMAKE_BINARY_DIR}/Doxyfile"
    WORKING_DIRECTORY "${PHYSLAB_ROOT}"
    COMMENT "Building the Doxygen site in ${CMAKE_BINARY_DIR}/docs/html"
    VERBATIM)
endif()
