// The object the precompiled Eigen headers of physlab_pch are built for (cmake/PhysLab.cmake).
