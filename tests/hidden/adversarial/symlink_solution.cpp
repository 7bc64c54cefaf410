// adversarial: the lab file is a symbolic link to the reference solution
// symlink: labs/01_particles/diagnostics.cpp -> {ROOT}/solutions/01_particles/diagnostics.cpp
// quick
