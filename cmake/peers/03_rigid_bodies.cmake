# Optional peer for bench_03_rigid_bodies: Bullet's rigid bodies (double-precision build) and
# their gyroscopic modes. Found quietly; without it the benchmark reports "not installed".
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(PHYSLAB_BULLET_RIGID QUIET IMPORTED_TARGET bullet-float64)
  if(PHYSLAB_BULLET_RIGID_FOUND)
    target_link_libraries(${PHYSLAB_BENCH_TARGET} PRIVATE PkgConfig::PHYSLAB_BULLET_RIGID)
    target_compile_definitions(${PHYSLAB_BENCH_TARGET} PRIVATE PHYSLAB_HAVE_BULLET)
  endif()
endif()
