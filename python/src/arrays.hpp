#pragma once
/// @file
/// NumPy arrays in and out of the bindings: every array a user passes is checked for its dtype
/// and shape here, and a wrong one raises ValueError naming the argument, expected and got (as
/// walkgen's own messages do), before any of it reaches C++.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <sstream>
#include <string>

#include "walkgen/core/exceptions.hpp"

namespace walkgen::python {

namespace py = pybind11;

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstRowMap = Eigen::Map<const RowMatrix>;
using ConstVectorMap = Eigen::Map<const Eigen::VectorXd>;

/// An array of float64 converted from `object` (real numbers only: float, int, unsigned or
/// bool arrays and nested sequences of numbers). A sequence that is not numeric, a complex or
/// object array raise ValueError naming `where`.
inline py::array_t<double, py::array::c_style> as_float_array(const py::handle& object,
                                                              const std::string& where) {
  py::array array;
  try {
    array = py::array::ensure(object);
  } catch (const py::error_already_set&) {
    array = py::array();
  }
  if (!array) {
    throw invalid_argument(detail::expected_got(where.c_str(), "an array of real numbers",
                                                std::string(py::str(py::type::of(object)))));
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw invalid_argument(
        detail::expected_got(where.c_str(), "an array of real numbers (float, int)",
                             "dtype " + std::string(py::str(array.dtype())),
                             "convert it with numpy.asarray(value, dtype=float)"));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
}

/// "(2, 3)" for a shape.
inline std::string shape_string(const py::array& array) {
  std::ostringstream os;
  os << "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k) os << (k ? ", " : "") << array.shape(k);
  os << (array.ndim() == 1 ? ",)" : ")");
  return os.str();
}

/// A float64 vector of `size` entries (a 1-D array, or a column or row of a 2-D one).
class VectorArg {
 public:
  VectorArg(const py::handle& object, const std::string& where, Eigen::Index size)
      : array_(as_float_array(object, where)) {
    const bool ok = array_.ndim() == 1 ? array_.shape(0) == size
                                       : array_.ndim() == 2 && array_.size() == size &&
                                             (array_.shape(0) == 1 || array_.shape(1) == 1);
    if (!ok) {
      throw invalid_argument(
          detail::expected_got(where.c_str(), "a vector of shape (" + std::to_string(size) + ",)",
                               "shape " + shape_string(array_)));
    }
  }
  ConstVectorMap map() const { return ConstVectorMap(array_.data(), array_.size()); }

 private:
  py::array_t<double, py::array::c_style> array_;
};

/// A float64 matrix of rows × cols, row-major as NumPy's default.
class MatrixArg {
 public:
  MatrixArg(const py::handle& object, const std::string& where, Eigen::Index rows,
            Eigen::Index cols)
      : array_(as_float_array(object, where)) {
    const bool ok = array_.ndim() == 2 && array_.shape(0) == rows && array_.shape(1) == cols;
    // A problem without rows may pass A as an empty array of any shape.
    const bool empty_ok = rows == 0 && array_.size() == 0;
    if (!ok && !empty_ok) {
      throw invalid_argument(detail::expected_got(
          where.c_str(),
          "a matrix of shape (" + std::to_string(rows) + ", " + std::to_string(cols) + ")",
          "shape " + shape_string(array_)));
    }
  }
  ConstRowMap map(Eigen::Index rows, Eigen::Index cols) const {
    return ConstRowMap(array_.data(), rows, cols);
  }

 private:
  py::array_t<double, py::array::c_style> array_;
};

/// A new NumPy array holding a copy of `m` (the result outlives the solver's buffers).
template <typename Derived>
py::array_t<double> to_numpy(const Eigen::DenseBase<Derived>& m) {
  if (Derived::ColsAtCompileTime == 1) {
    py::array_t<double> out(static_cast<py::ssize_t>(m.rows()));
    auto view = out.template mutable_unchecked<1>();
    for (Eigen::Index i = 0; i < m.rows(); ++i) view(i) = m(i, 0);
    return out;
  }
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = out.template mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  }
  return out;
}

}  // namespace walkgen::python
