#include "NumpyConversion.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <string_view>

namespace py = pybind11;

namespace coulomb::python {
namespace {

std::string shapeText(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    text += (d ? ", " : "") + std::to_string(a.shape(d)) + (a.ndim() == 1 ? "," : "");
  return text + ")";
}

std::string sizeText(Eigen::Index n) {
  return n < 0 ? std::string("n") : std::to_string(n);
}

// The object as an array whose dtype is one of `kinds` (NumPy kind letters), else ValueError.
py::array checkedArray(py::handle object, const std::string& name, std::string_view kinds,
                       const char* expected) {
  if (object.is_none()) throw py::value_error(name + ": expected " + expected + ", got None");
  py::array a = py::array::ensure(object);
  if (!a) throw py::value_error(name + ": expected " + expected + " (array-like)");
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string_view::npos)
    throw py::value_error(name + ": expected " + expected + ", got dtype " +
                          std::string(py::str(a.dtype())));
  return a;
}

}  // namespace

Eigen::VectorXd toVector(py::handle object, const std::string& name, Eigen::Index expectedSize) {
  const std::string expected = "a float array of shape (" + sizeText(expectedSize) + ",)";
  py::array a = checkedArray(object, name, "biuf", expected.c_str());
  if (a.ndim() != 1 || (expectedSize >= 0 && a.shape(0) != expectedSize))
    throw py::value_error(name + ": expected shape (" + sizeText(expectedSize) + ",), got " +
                          shapeText(a));
  auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  Eigen::VectorXd v(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) v[i] = doubles.at(i);
  return v;
}

Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1> toIndices(py::handle object,
                                                         const std::string& name) {
  py::array a = checkedArray(object, name, "iu", "an integer array of shape (k,)");
  if (a.ndim() != 1) throw py::value_error(name + ": expected shape (k,), got " + shapeText(a));
  auto values = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
  Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1> v(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) v[i] = static_cast<Eigen::Index>(values.at(i));
  return v;
}

Eigen::MatrixXd toMatrix(py::handle object, const std::string& name, Eigen::Index rows,
                         Eigen::Index cols) {
  const std::string expected =
      "a float array of shape (" + sizeText(rows) + ", " + sizeText(cols) + ")";
  py::array a = checkedArray(object, name, "biuf", expected.c_str());
  if (a.ndim() != 2 || (rows >= 0 && a.shape(0) != rows) || (cols >= 0 && a.shape(1) != cols))
    throw py::value_error(name + ": expected shape (" + sizeText(rows) + ", " + sizeText(cols) +
                          "), got " + shapeText(a));
  auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  Eigen::MatrixXd m(a.shape(0), a.shape(1));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (py::ssize_t j = 0; j < a.shape(1); ++j) m(i, j) = doubles.at(i, j);
  return m;
}

py::array_t<double> toNumpy(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

py::array_t<double> toNumpy(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return out;
}

geometry::Pose poseFrom(pybind11::handle position, pybind11::handle rotation) {
  geometry::Pose pose = geometry::Pose::translation(toVector(position, "position", 3));
  if (!rotation.is_none()) {
    const Eigen::VectorXd q = toVector(rotation, "rotation", 4);  // (w, x, y, z)
    pose.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    if (!(pose.rotation.norm() > 1e-9))
      throw engine::CoulombError("rotation: expected a non-zero quaternion (w, x, y, z)");
    pose.rotation.normalize();
  }
  return pose;
}

}  // namespace coulomb::python
