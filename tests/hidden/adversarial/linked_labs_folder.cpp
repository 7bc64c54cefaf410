// adversarial: the whole labs/ folder is a link to the reference solutions
// symlink: labs -> {ROOT}/solutions
