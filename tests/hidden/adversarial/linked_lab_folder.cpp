// adversarial: the lab folder is a link to the reference solution's folder, so its files are regular files reached through a link
// symlink: labs/01_particles -> {ROOT}/solutions/01_particles
// quick
