// adversarial: the lab file includes the reference solution by a relative path
// mode: replace
#include "../../solutions/01_particles/diagnostics.cpp"
