/// \file dense_lu.hpp
/// \brief Eigen's dense LU with partial pivoting on a dynamic matrix, compiled once in the framework.
///
/// Lab 1's implicit methods and Lab 6's pivoting solve with Eigen::PartialPivLU<MatX>. Its
/// members are heavy templates: instantiating and optimising them took a quarter of the compile
/// of Lab 6's lcp.cpp (7.2 s against 5.5 s without) and 40 % of Lab 1's integrators.cpp, in every
/// build and every grade of those files. Declared here as instantiated elsewhere (`extern
/// template`), a lab file that includes this header calls the framework's one copy
/// (common/src/dense_lu.cpp, built with the same flags) rather than compiling its own; its code
/// and results are the same.
#pragma once

#include <Eigen/LU>

extern template class Eigen::PartialPivLU<Eigen::MatrixXd>;
