#pragma once
// Reader and writer of the "fc3d-text 1" format (spec: the fc3d corpus README, summarized here):
//   # comment lines, only before the magic line ("# family: X" is kept)
//   fc3d-text 1
//   name <token>
//   contacts <nc>
//   mu <nc numbers>
//   q <3 nc numbers>          per contact (normal, tangent1, tangent2)
//   W <nb>  then nb records "<i> <j> <9 numbers, row-major 3x3 block>", sorted by (i, j),
//           diagonal blocks present, zero blocks omitted
//   end
// Whitespace separated; numbers are read with strtod (round trip exact). Errors name the file,
// the line and what was expected.
#include <coulomb/solvers/ContactProblem.hpp>

#include <iosfwd>
#include <optional>
#include <string>

namespace coulomb::solvers {

struct Fc3dReadResult {
  std::optional<ContactProblem> problem;  // set on success
  std::string family;                     // from "# family: X", may be empty
  std::string error;                      // "FILE:LINE: what is wrong" on failure
};

Fc3dReadResult readFc3dText(const std::string& path);
Fc3dReadResult parseFc3dText(std::istream& in, const std::string& sourceName);

// Writes a pure contact problem (isotropic Contact3D blocks only) with shortest round-trip
// numbers; returns an error message, empty on success.
std::string writeFc3dText(const ContactProblem& problem, std::ostream& out,
                          const std::string& family = {});

// r as whitespace-separated numbers, one contact (3 numbers) per line, round-trip exact.
void writeVector(const Eigen::VectorXd& v, std::ostream& out, int perLine = 3);

// The inverse of writeVector: exactly `size` finite numbers, whitespace separated (a captured
// warm start, `coulomb solve --start`). nullopt with `error` = "FILE: what is wrong" otherwise.
std::optional<Eigen::VectorXd> readVector(const std::string& path, Eigen::Index size,
                                          std::string& error);

}  // namespace coulomb::solvers
