# Optional peer for bench_02_springs: Bullet's soft-body cloth, double-precision build. Found
# quietly; without it the benchmark reports "not installed".
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(PHYSLAB_BULLET QUIET IMPORTED_TARGET bullet-float64)
  if(PHYSLAB_BULLET_FOUND)
    target_link_libraries(${PHYSLAB_BENCH_TARGET} PRIVATE PkgConfig::PHYSLAB_BULLET)
    target_compile_definitions(${PHYSLAB_BENCH_TARGET} PRIVATE PHYSLAB_HAVE_BULLET)
    message(STATUS "bench_02_springs: comparing with Bullet ${PHYSLAB_BULLET_VERSION}")
  endif()
endif()
