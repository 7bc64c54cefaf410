# Optional peer for bench_03_rigid_bodies: Bullet's rigid bodies and gyroscopic modes.
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
