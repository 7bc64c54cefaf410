// adversarial: the lab file is a symbolic link to /etc/passwd, hoping the compiler quotes it
// symlink: labs/01_particles/diagnostics.cpp -> /etc/passwd
// secret: root:x:0:0
