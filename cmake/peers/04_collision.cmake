# Optional peers for bench_04_collision: Bullet's btDbvtBroadphase (and box-box detector) and
# FCL's dynamic AABB tree manager. Each is linked, with PHYSLAB_HAVE_BULLET / PHYSLAB_HAVE_FCL
# defined, only when pkg-config finds it (and the standard library is the one it was built for:
# PHYSLAB_CXX_PEERS).
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND AND PHYSLAB_CXX_PEERS)
  if(NOT TARGET PkgConfig::PHYSLAB_FCL)
    pkg_check_modules(PHYSLAB_FCL QUIET IMPORTED_TARGET GLOBAL fcl)
    if(TARGET PkgConfig::PHYSLAB_FCL)
      # fcl.pc asks for -std=c++11, which would fight the project's C++17: drop it.
      get_target_property(fcl_options PkgConfig::PHYSLAB_FCL INTERFACE_COMPILE_OPTIONS)
      if(fcl_options)
        list(FILTER fcl_options EXCLUDE REGEX "^-std=")
        set_target_properties(PkgConfig::PHYSLAB_FCL PROPERTIES INTERFACE_COMPILE_OPTIONS "${fcl_options}")
      endif()
    endif()
  endif()
  if(TARGET PkgConfig::PHYSLAB_FCL)
    target_link_libraries(${PHYSLAB_BENCH_TARGET} PRIVATE PkgConfig::PHYSLAB_FCL)
    target_compile_definitions(${PHYSLAB_BENCH_TARGET} PRIVATE PHYSLAB_HAVE_FCL)
    message(STATUS "${PHYSLAB_BENCH_TARGET}: comparing with FCL (fcl ${PHYSLAB_FCL_VERSION})")
  endif()
endif()
