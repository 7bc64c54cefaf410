# Optional peers for bench_03_rigid_bodies: Bullet's gyroscopic modes and MuJoCo's integrators.
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
physlab_link_mujoco(${PHYSLAB_BENCH_TARGET})
