# Optional peer for bench_05_impulses: Bullet's btDiscreteDynamicsWorld with its sequential-impulse
# solver, on the same box rain and Newton's cradle. Linked, with PHYSLAB_HAVE_BULLET defined, only
# when pkg-config finds bullet-float64 (the double build, so that both engines step in doubles).
physlab_link_bullet(${PHYSLAB_BENCH_TARGET})
