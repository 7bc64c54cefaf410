# Optional peer for bench_02_springs: Bullet's soft-body cloth.
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
