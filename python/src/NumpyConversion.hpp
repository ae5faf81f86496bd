#pragma once
// NumPy arrays in and out of Eigen, with the checks docs/python.md promises: a wrong shape or a
// dtype that is not a real number is a ValueError naming the argument and the expected shape.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <coulomb/geometry/Pose.hpp>

#include <Eigen/Core>

#include <string>

namespace coulomb::python {

/// A 1-d array of `expectedSize` real numbers (-1: any size) as a vector (copied). `name` is the
/// argument's name in the message.
Eigen::VectorXd toVector(pybind11::handle object, const std::string& name,
                         Eigen::Index expectedSize = -1);
/// A 1-d integer array (indices of triplets) as a vector of Index.
Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1> toIndices(pybind11::handle object,
                                                         const std::string& name);
/// A 2-d array of real numbers of shape (rows, cols) (-1: any) as a matrix (copied).
Eigen::MatrixXd toMatrix(pybind11::handle object, const std::string& name, Eigen::Index rows,
                         Eigen::Index cols);

/// A pose from a position (3) and an optional rotation quaternion (w, x, y, z; None: identity),
/// normalized; CoulombError for a zero quaternion.
geometry::Pose poseFrom(pybind11::handle position, pybind11::handle rotation);

/// Fresh NumPy arrays owning a copy.
pybind11::array_t<double> toNumpy(const Eigen::VectorXd& v);
pybind11::array_t<double> toNumpy(const Eigen::MatrixXd& m);

}  // namespace coulomb::python
