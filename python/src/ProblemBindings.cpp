// coulomb.Block, coulomb.ContactProblem and the fc3d-text files (docs/python.md "Contact
// problems"): a problem is built from NumPy (W dense, scipy-sparse or (rows, cols, values)
// triplets; q; mu or a list of blocks), validated once at construction.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "Bindings.hpp"
#include "NumpyConversion.hpp"

namespace py = pybind11;
using coulomb::engine::CoulombError;
using coulomb::solvers::BlockKind;
using coulomb::solvers::BlockSparseMatrix;
using coulomb::solvers::ConstraintBlock;
using coulomb::solvers::ContactProblem;
using coulomb::solvers::DelassusOperator;

namespace coulomb::python {
namespace {

std::string blockRepr(const ConstraintBlock& b) {
  std::ostringstream s;
  s.precision(17);
  switch (b.kind) {
    case BlockKind::Equality:
      s << "Block.equality()";
      break;
    case BlockKind::Unilateral:
      s << "Block.unilateral()";
      break;
    case BlockKind::Bounded:
      s << "Block.bounded(" << b.lower << ", " << b.upper << ")";
      break;
    case BlockKind::Contact3D:
      if (b.anisotropic)
        s << "Block.anisotropic(" << b.mu1 << ", " << b.mu2 << ")";
      else
        s << "Block.contact(" << b.mu << ")";
      break;
  }
  return s.str();
}

// W from (rows, cols, values) over the partition of the blocks: entries of one (block row, block
// column) are gathered into one block, duplicates summed (as scipy's COO), diagonal blocks kept.
BlockSparseMatrix fromTriplets(py::handle rowsObject, py::handle colsObject,
                               py::handle valuesObject, const std::vector<int>& sizes) {
  const auto rows = toIndices(rowsObject, "W rows");
  const auto cols = toIndices(colsObject, "W cols");
  const Eigen::VectorXd values = toVector(valuesObject, "W values", rows.size());
  if (cols.size() != rows.size())
    throw py::value_error("W cols: expected shape (" + std::to_string(rows.size()) +
                          ",) like the rows, got (" + std::to_string(cols.size()) + ",)");
  std::vector<int> offsets{0};
  for (int s : sizes) offsets.push_back(offsets.back() + s);
  const Eigen::Index n = offsets.back();
  auto blockOf = [&](Eigen::Index i) {
    return static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), i) - offsets.begin()) -
           1;
  };
  std::map<std::pair<int, int>, std::vector<double>> blocks;
  for (int b = 0; b < static_cast<int>(sizes.size()); ++b)
    blocks[{b, b}].assign(static_cast<std::size_t>(sizes[b] * sizes[b]), 0.0);
  for (Eigen::Index k = 0; k < rows.size(); ++k) {
    if (rows[k] < 0 || rows[k] >= n || cols[k] < 0 || cols[k] >= n)
      throw py::value_error("W triplet " + std::to_string(k) + ": index (" +
                            std::to_string(rows[k]) + ", " + std::to_string(cols[k]) +
                            ") outside the " + std::to_string(n) + " x " + std::to_string(n) +
                            " matrix");
    const int bi = blockOf(rows[k]), bj = blockOf(cols[k]);
    std::vector<double>& block = blocks[{bi, bj}];
    if (block.empty()) block.assign(static_cast<std::size_t>(sizes[bi] * sizes[bj]), 0.0);
    block[static_cast<std::size_t>((rows[k] - offsets[bi]) * sizes[bj] + cols[k] - offsets[bj])] +=
        values[k];
  }
  std::vector<solvers::MatrixBlockEntry> entries;
  entries.reserve(blocks.size());
  for (auto& [index, block] : blocks) entries.push_back({index.first, index.second, block});
  return BlockSparseMatrix(sizes, std::move(entries));
}

DelassusOperator toOperator(py::handle W, const std::vector<int>& sizes, Eigen::Index n) {
  if (py::hasattr(W, "tocoo")) {  // scipy.sparse, without depending on scipy
    py::object coo = W.attr("tocoo")();
    const auto shape = coo.attr("shape").cast<std::pair<Eigen::Index, Eigen::Index>>();
    if (shape.first != n || shape.second != n)
      throw py::value_error("W: expected shape (" + std::to_string(n) + ", " + std::to_string(n) +
                            ") to match q, got (" + std::to_string(shape.first) + ", " +
                            std::to_string(shape.second) + ")");
    return DelassusOperator::blockSparse(
        fromTriplets(coo.attr("row"), coo.attr("col"), coo.attr("data"), sizes));
  }
  if (py::isinstance<py::tuple>(W) && py::len(W) == 3) {
    auto t = W.cast<py::tuple>();
    return DelassusOperator::blockSparse(fromTriplets(t[0], t[1], t[2], sizes));
  }
  return DelassusOperator::dense(toMatrix(W, "W", n, n));
}

std::vector<ConstraintBlock> blocksFrom(const py::object& mu, const py::object& blocks,
                                        Eigen::Index n) {
  if (mu.is_none() == blocks.is_none())
    throw py::value_error("ContactProblem: give either mu (pure contact problem) or blocks");
  std::vector<ConstraintBlock> out;
  if (!mu.is_none()) {
    if (n % 3 != 0)
      throw py::value_error("q: a pure contact problem has 3 unknowns per contact, got " +
                            std::to_string(n));
    const Eigen::VectorXd m = toVector(mu, "mu", n / 3);
    for (Eigen::Index c = 0; c < m.size(); ++c) out.push_back(ConstraintBlock::contact(m[c]));
    return out;
  }
  out = blocks.cast<std::vector<ConstraintBlock>>();
  Eigen::Index total = 0;
  for (const ConstraintBlock& b : out) total += b.size();
  if (total != n)
    throw py::value_error("blocks: their sizes add up to " + std::to_string(total) +
                          " unknowns, q has " + std::to_string(n));
  return out;
}

void setWarmStart(ContactProblem& p, const py::object& start) {
  if (start.is_none())
    p.warmStart.reset();
  else
    p.warmStart = toVector(start, "warm_start", p.size());
}

ContactProblem makeProblem(const py::object& W, const py::object& q, const py::object& mu,
                           const py::object& blocks, std::string name,
                           const py::object& warmStart) {
  ContactProblem p;
  p.q = toVector(q, "q");
  p.blocks = blocksFrom(mu, blocks, p.q.size());
  p.W = toOperator(W, p.blockSizes(), p.q.size());
  p.name = std::move(name);
  setWarmStart(p, warmStart);
  if (auto error = p.validate()) throw CoulombError("ContactProblem: " + *error);
  return p;
}

BlockSparseMatrix blockSparseOf(const ContactProblem& p) {
  if (const BlockSparseMatrix* W = p.W.blockSparseMatrix()) return *W;
  return p.W.toBlockSparse(p.blockSizes());
}

// The stored entries of W (exact zero blocks dropped) as (rows, cols, values).
py::tuple triplets(const ContactProblem& p) {
  const BlockSparseMatrix W = blockSparseOf(p);
  std::vector<long long> rows, cols;
  std::vector<double> values;
  for (int i = 0; i < W.blockCount(); ++i)
    for (int k = W.rowBegin(i); k < W.rowEnd(i); ++k) {
      const int j = W.blockColumn(k);
      for (int r = 0; r < W.blockSize(i); ++r)
        for (int c = 0; c < W.blockSize(j); ++c) {
          rows.push_back(W.blockOffset(i) + r);
          cols.push_back(W.blockOffset(j) + c);
          values.push_back(W.blockValues(k)[r * W.blockSize(j) + c]);
        }
    }
  return py::make_tuple(
      py::array_t<long long>(static_cast<py::ssize_t>(rows.size()), rows.data()),
      py::array_t<long long>(static_cast<py::ssize_t>(cols.size()), cols.data()),
      py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data()));
}

Eigen::MatrixXd denseOf(const ContactProblem& p) {
  if (const Eigen::MatrixXd* W = p.W.denseMatrix()) return *W;
  return blockSparseOf(p).toDense();
}

const char* storageName(DelassusOperator::Storage s) {
  switch (s) {
    case DelassusOperator::Storage::Dense:
      return "dense";
    case DelassusOperator::Storage::BlockSparse:
      return "block_sparse";
    case DelassusOperator::Storage::BodySpace:
      return "body_space";
    case DelassusOperator::Storage::MatrixFree:
      return "matrix_free";
  }
  return "dense";
}

ContactProblem parsed(solvers::Fc3dReadResult read) {
  if (!read.problem) throw CoulombError(read.error);
  return std::move(*read.problem);
}

std::string fc3dText(const ContactProblem& p, const std::string& family) {
  std::ostringstream out;
  if (std::string error = solvers::writeFc3dText(p, out, family); !error.empty())
    throw CoulombError(error);
  return out.str();
}

}  // namespace

void bindProblem(py::module_& m) {
  py::class_<ConstraintBlock>(m, "Block",
                              "One block of unknowns: a 3-row contact (N, T1, T2) or a scalar row")
      .def_static("contact", &ConstraintBlock::contact, py::arg("mu"),
                  "Contact with isotropic Coulomb friction mu (3 unknowns)")
      .def_static("anisotropic", &ConstraintBlock::anisotropicContact, py::arg("mu1"),
                  py::arg("mu2"), "Contact with friction mu1 along T1 and mu2 along T2")
      .def_static("equality", &ConstraintBlock::equality, "Bilateral row: u = 0, r free")
      .def_static("bounded", &ConstraintBlock::bounded, py::arg("lower"), py::arg("upper"),
                  "Box-complementarity row: lower <= r <= upper (motors, joint friction)")
      .def_static("unilateral", &ConstraintBlock::unilateral,
                  "0 <= r complementary to u >= 0 (limits, frictionless contacts)")
      .def_property_readonly(
          "kind", [](const ConstraintBlock& b) { return solvers::blockKindName(b.kind); })
      .def_property_readonly("size", &ConstraintBlock::size)
      .def_readonly("mu", &ConstraintBlock::mu)
      .def_readonly("mu1", &ConstraintBlock::mu1)
      .def_readonly("mu2", &ConstraintBlock::mu2)
      .def_readonly("lower", &ConstraintBlock::lower)
      .def_readonly("upper", &ConstraintBlock::upper)
      .def_readonly("is_anisotropic", &ConstraintBlock::anisotropic)
      .def("__repr__", &blockRepr)
      .def("__eq__",
           [](const ConstraintBlock& a, const ConstraintBlock& b) {
             return a.kind == b.kind && a.mu == b.mu && a.anisotropic == b.anisotropic &&
                    a.mu1 == b.mu1 && a.mu2 == b.mu2 && a.lower == b.lower && a.upper == b.upper;
           })
      .def(py::pickle(
          [](const ConstraintBlock& b) {
            return py::make_tuple(static_cast<int>(b.kind), b.mu, b.anisotropic, b.mu1, b.mu2,
                                  b.lower, b.upper);
          },
          [](const py::tuple& t) {
            if (py::len(t) != 7) throw py::value_error("Block: bad pickled state");
            ConstraintBlock b;
            const int kind = t[0].cast<int>();
            if (kind < 0 || kind > static_cast<int>(BlockKind::Contact3D))
              throw py::value_error("Block: bad pickled kind");
            b.kind = static_cast<BlockKind>(kind);
            b.mu = t[1].cast<double>();
            b.anisotropic = t[2].cast<bool>();
            b.mu1 = t[3].cast<double>();
            b.mu2 = t[4].cast<double>();
            b.lower = t[5].cast<double>();
            b.upper = t[6].cast<double>();
            return b;
          }));

  py::class_<ContactProblem>(
      m, "ContactProblem",
      "Find r with u = W r + q and, block by block, the Coulomb cone (contacts) or the row's law "
      "(docs/solvers.md). W: a dense (n, n) array, a scipy.sparse matrix or (rows, cols, values) "
      "triplets; give mu (one per contact, n = 3 contacts) or blocks.")
      .def(py::init(&makeProblem), py::arg("W"), py::arg("q"), py::arg("mu") = py::none(),
           py::kw_only(), py::arg("blocks") = py::none(), py::arg("name") = "",
           py::arg("warm_start") = py::none())
      .def_readwrite("name", &ContactProblem::name)
      .def_property_readonly("size", &ContactProblem::size, "number of scalar unknowns")
      .def_property_readonly("contact_count", &ContactProblem::contactCount)
      .def_property_readonly("block_count", [](const ContactProblem& p) { return p.blocks.size(); })
      .def_property_readonly("blocks", [](const ContactProblem& p) { return p.blocks; })
      .def_property_readonly("q", [](const ContactProblem& p) { return toNumpy(p.q); })
      .def_property_readonly(
          "mu",
          [](const ContactProblem& p) {
            Eigen::VectorXd mu(p.contactCount());
            Eigen::Index c = 0;
            for (const ConstraintBlock& b : p.blocks)
              if (b.isContact()) mu[c++] = b.mu;
            return toNumpy(mu);
          },
          "friction coefficient of each contact block")
      .def_property_readonly(
          "W", [](const ContactProblem& p) { return toNumpy(denseOf(p)); }, "W as a dense array")
      .def("W_triplets", &triplets,
           "the stored entries of W as (rows, cols, values), e.g. for scipy.sparse.coo_matrix")
      .def_property_readonly("storage",
                             [](const ContactProblem& p) { return storageName(p.W.storage()); })
      .def_property(
          "warm_start",
          [](const ContactProblem& p) -> py::object {
            if (!p.warmStart) return py::none();
            return toNumpy(*p.warmStart);
          },
          &setWarmStart, "initial impulses r (or None): used when a solve asks for a warm start")
      .def("to_fc3d", &fc3dText, py::arg("family") = "",
           "the problem in fc3d-text 1 (pure contact problems only)")
      .def("__repr__",
           [](const ContactProblem& p) {
             return "<coulomb.ContactProblem '" + p.name + "': " + std::to_string(p.size()) +
                    " unknowns, " + std::to_string(p.contactCount()) + " contacts, " +
                    storageName(p.W.storage()) + " W>";
           })
      .def(py::pickle(
          [](const ContactProblem& p) {
            // Dense W stays dense: a pickled problem solves bit-identically (Dask workers).
            py::object W = p.W.denseMatrix() ? py::object(toNumpy(*p.W.denseMatrix()))
                                             : py::object(triplets(p));
            return py::make_tuple(p.name, p.blocks, W, toNumpy(p.q),
                                  p.warmStart ? py::object(toNumpy(*p.warmStart)) : py::none());
          },
          [](const py::tuple& t) {
            if (py::len(t) != 5) throw py::value_error("ContactProblem: bad pickled state");
            return makeProblem(t[2], t[3], py::none(), t[1], t[0].cast<std::string>(), t[4]);
          }));

  m.def(
      "read_fc3d",
      [](const std::string& path) {
        if (!std::filesystem::exists(path)) {
          PyErr_SetString(PyExc_FileNotFoundError, (path + ": no such file").c_str());
          throw py::error_already_set();
        }
        return parsed(solvers::readFc3dText(path));
      },
      py::arg("path"), "Reads a problem in fc3d-text 1 (errors: coulomb.Error naming FILE:LINE)");
  m.def(
      "parse_fc3d",
      [](const std::string& text, const std::string& source) {
        std::istringstream in(text);
        return parsed(solvers::parseFc3dText(in, source));
      },
      py::arg("text"), py::arg("source") = "<string>", "A problem from fc3d-text 1 text");
  m.def(
      "write_fc3d",
      [](const ContactProblem& p, const std::string& path, const std::string& family) {
        const std::string text = fc3dText(p, family);
        std::ofstream out(path);
        out << text;
        if (!out.flush()) throw CoulombError(path + ": cannot write");
      },
      py::arg("problem"), py::arg("path"), py::arg("family") = "",
      "Writes a pure contact problem in fc3d-text 1 (round-trip exact)");
}

}  // namespace coulomb::python
