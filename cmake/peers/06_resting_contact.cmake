# Optional peers for bench_06_resting_contact: Bullet's btDiscreteDynamicsWorld (sequential
# impulses) and ODE's dWorldStep (Dantzig LCP) and dWorldQuickStep (PGS), on the same box
# pyramids. Bullet is linked, with PHYSLAB_HAVE_BULLET defined, only when pkg-config finds
# bullet-float64; ODE, with PHYSLAB_HAVE_ODE, only when pkg-config finds ode built in double
# precision (its ode.pc says precision=dDOUBLE), so that every engine steps in doubles.
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  if(NOT TARGET PkgConfig::PHYSLAB_ODE)
    pkg_check_modules(PHYSLAB_ODE QUIET IMPORTED_TARGET GLOBAL ode)
  endif()
  if(TARGET PkgConfig::PHYSLAB_ODE)
    pkg_get_variable(physlab_ode_precision ode precision)
    if(physlab_ode_precision STREQUAL "dDOUBLE")
      target_link_libraries(${PHYSLAB_BENCH_TARGET} PRIVATE PkgConfig::PHYSLAB_ODE)
      # ODE's headers pick the precision from dIDEDOUBLE; the default is double too, but say so
      target_compile_definitions(${PHYSLAB_BENCH_TARGET} PRIVATE PHYSLAB_HAVE_ODE dIDEDOUBLE)
      message(STATUS "${PHYSLAB_BENCH_TARGET}: comparing with ODE (ode ${PHYSLAB_ODE_VERSION}, double)")
    else()
      message(STATUS "${PHYSLAB_BENCH_TARGET}: ODE found but built with ${physlab_ode_precision}, not compared")
    endif()
  endif()
endif()
