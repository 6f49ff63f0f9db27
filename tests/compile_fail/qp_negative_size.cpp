// Must not compile: a negative compile-time size is refused with a "walkgen: ..." sentence
// (docs/design.md convention 4). Built only by the compile_fail_qp_size ctest.

#include "walkgen/qp/dense_qp.hpp"

int main() {
  walkgen::DenseQp<double, -3, 4> qp;
  return static_cast<int>(qp.num_vars());
}
