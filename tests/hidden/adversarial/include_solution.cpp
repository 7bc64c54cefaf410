// adversarial: the lab file includes the reference solution by absolute and relative path
// mode: replace
// quick
#include "{ROOT}/solutions/01_particles/diagnostics.cpp"
