// SPDX-License-Identifier: MIT
// Data of TR48 (TEST19 #21), see luksan_vlcek_tr48_data.cpp.
#pragma once

#include <Eigen/Core>

namespace frictopt::optim::detail {

struct Tr48Data {
  Eigen::MatrixXd a;       ///< 48×48 costs a_ij (symmetric, 100000 on the diagonal)
  Eigen::VectorXd d;       ///< demands d_j
  Eigen::VectorXd s;       ///< supplies s_i
  Eigen::VectorXd x_star;  ///< the report's minimizer, f(x*) = f* = −638565
};

const Tr48Data& tr48_data();

}  // namespace frictopt::optim::detail
