# `docs` target: the Doxygen site (main page, handouts, conventions, API of common/) with the
# charts the demos wrote into ${PHYSLAB_CHART_DIR}. Warnings in common/ fail the build.
# A handout shows a demo chart with \chart{file,caption}. In the instructor's tree the demos draw
# with the reference and that chart is shown. In a student copy the demos draw with the student's
# code: the reference's chart (docs/figures/reference/, shipped by ./physlab publish) is shown with
# the student's beside it, or a placeholder saying their code cannot draw it yet.
set(PHYSLAB_CHART_DIR "${CMAKE_BINARY_DIR}/charts" CACHE PATH "Where demos write charts for the docs")
find_package(Doxygen QUIET OPTIONAL_COMPONENTS dot)
if(DOXYGEN_FOUND)
  set(PHYSLAB_HAVE_DOT NO)
  if(DOXYGEN_DOT_FOUND)
    set(PHYSLAB_HAVE_DOT YES)
  endif()
  # MathJax from Debian's libjs-mathjax, copied beside the pages, so that formulas render with no
  # network (a student on a train, an exam room).
  find_path(PHYSLAB_MATHJAX_DIR MathJax.js PATHS /usr/share/javascript/mathjax NO_DEFAULT_PATH)
  set(mathjax_copy "")
  if(PHYSLAB_MATHJAX_DIR)
    set(PHYSLAB_MATHJAX_RELPATH mathjax)
    set(html "${CMAKE_BINARY_DIR}/docs/html/mathjax")
    set(mathjax_copy COMMAND "${CMAKE_COMMAND}" -E copy "${PHYSLAB_MATHJAX_DIR}/MathJax.js" "${html}/MathJax.js")
    foreach(part config extensions fonts jax localization)
      list(APPEND mathjax_copy COMMAND "${CMAKE_COMMAND}" -E copy_directory "${PHYSLAB_MATHJAX_DIR}/${part}" "${html}/${part}")
    endforeach()
  else()
    set(PHYSLAB_MATHJAX_RELPATH "")  # Doxygen's default: the MathJax CDN
    message(WARNING "libjs-mathjax is not installed: the docs' formulas need the network to render")
  endif()
  set(placeholders "")
  if(PHYSLAB_HAVE_SOLUTIONS)
    set(PHYSLAB_IMAGE_PATH "${PHYSLAB_CHART_DIR} ${PHYSLAB_ROOT}/docs/figures")
    set(PHYSLAB_CHART_ALIAS [=[chart{2}=\image html \1 \"\2 (reference solution)\"]=])
  else()
    find_package(Python3 REQUIRED COMPONENTS Interpreter)
    set(not_drawn "${CMAKE_BINARY_DIR}/docs/not-drawn")
    set(PHYSLAB_IMAGE_PATH
        "${PHYSLAB_CHART_DIR} ${not_drawn} ${PHYSLAB_ROOT}/docs/figures ${PHYSLAB_ROOT}/docs/figures/reference")
    set(PHYSLAB_CHART_ALIAS [=[chart{2}=<div class=\"physlab-pair\">^^\image html reference_\1 \"Reference solution: \2\"^^\image html \1 \"Your code: \2\"^^</div>]=])
    set(placeholders COMMAND "${Python3_EXECUTABLE}" "${PHYSLAB_ROOT}/tools/docs_figures.py" placeholders
        --docs "${PHYSLAB_ROOT}/docs" --charts "${PHYSLAB_CHART_DIR}" --out "${not_drawn}")
  endif()
  configure_file("${PHYSLAB_ROOT}/docs/Doxyfile.in" "${CMAKE_BINARY_DIR}/Doxyfile" @ONLY)
  add_custom_target(docs
    ${placeholders}
    COMMAND "${DOXYGEN_EXECUTABLE}" "${CMAKE_BINARY_DIR}/Doxyfile"
    ${mathjax_copy}
    WORKING_DIRECTORY "${PHYSLAB_ROOT}"
    COMMENT "Building the Doxygen site in ${CMAKE_BINARY_DIR}/docs/html"
    VERBATIM)
endif()
