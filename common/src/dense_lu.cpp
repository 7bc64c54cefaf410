// The framework's one instantiation of Eigen::PartialPivLU<MatX> (physlab/dense_lu.hpp).
#include "physlab/dense_lu.hpp"

template class Eigen::PartialPivLU<Eigen::MatrixXd>;
