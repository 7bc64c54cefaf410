// adversarial: a relative link to the reference's lab folder, as it resolves on Gradescope where the submission sits beside the instructor's tree
// file: labs/04_collision/gjk.cpp
// symlink: labs/04_collision -> {ROOT}/solutions/04_collision
// relative
// quick
