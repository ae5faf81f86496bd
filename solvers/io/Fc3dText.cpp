#include <coulomb/solvers/io/Fc3dText.hpp>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace coulomb::solvers {

namespace {

// Whitespace tokenizer that knows the line of every token.
class Tokens {
 public:
  Tokens(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

  // Comment lines before the magic line; returns the family if present.
  std::string skipComments() {
    std::string family;
    while (in_.peek() == '#') {
      std::string line;
      std::getline(in_, line);
      ++line_;
      const std::string key = "# family: ";
      if (line.compare(0, key.size(), key) == 0) family = line.substr(key.size());
    }
    return family;
  }

  bool next(std::string& tok) {
    tok.clear();
    int c;
    while ((c = in_.get()) != EOF && std::isspace(c))
      if (c == '\n') ++line_;
    if (c == EOF) return false;
    tokenLine_ = line_;
    tok.push_back(static_cast<char>(c));
    while ((c = in_.peek()) != EOF && !std::isspace(c)) tok.push_back(static_cast<char>(in_.get()));
    return true;
  }

  [[noreturn]] void fail(const std::string& what) const {
    std::ostringstream s;
    s << source_ << ":" << tokenLine_ << ": " << what;
    throw std::runtime_error(s.str());
  }
  void failAtEnd(const std::string& what) {
    tokenLine_ = line_;
    fail(what + ", found the end of the file");
  }

  void expectWord(const std::string& word, const std::string& hint) {
    std::string tok;
    if (!next(tok)) failAtEnd("expected '" + word + "' (" + hint + ")");
    if (tok != word) fail("expected '" + word + "' (" + hint + "), found '" + tok + "'");
  }

  double number(const std::string& what) {
    double v = 0.0;
    if (!nextNumber(what, v)) failAtEnd("expected " + what);
    return v;
  }

  // The next token as a finite number into `v`; false at the end of the input.
  bool nextNumber(const std::string& what, double& v) {
    std::string tok;
    if (!next(tok)) return false;
    char* end = nullptr;
    v = std::strtod(tok.c_str(), &end);
    if (end != tok.c_str() + tok.size() || tok.empty())
      fail("expected " + what + " (a number), found '" + tok + "'");
    if (!std::isfinite(v)) fail(what + " is '" + tok + "': must be finite");
    return true;
  }

  long integer(const std::string& what, long lo, long hi) {
    std::string tok;
    if (!next(tok)) failAtEnd("expected " + what);
    char* end = nullptr;
    const long v = std::strtol(tok.c_str(), &end, 10);
    if (end != tok.c_str() + tok.size() || tok.empty())
      fail("expected " + what + " (an integer), found '" + tok + "'");
    if (v < lo || v > hi) {
      std::ostringstream s;
      s << what << " = " << v << " is outside [" << lo << ", " << hi << "]";
      fail(s.str());
    }
    return v;
  }

 private:
  std::istream& in_;
  std::string source_;
  int line_ = 1, tokenLine_ = 1;
};

}  // namespace

Fc3dReadResult parseFc3dText(std::istream& in, const std::string& source) {
  Fc3dReadResult result;
  Tokens t(in, source);
  try {
    result.family = t.skipComments();
    t.expectWord("fc3d-text", "magic line 'fc3d-text 1'; comments only before it");
    if (t.integer("format version", 1, 1) != 1) t.fail("unsupported version");
    t.expectWord("name", "line 'name <name>'");
    std::string name;
    if (!t.next(name)) t.failAtEnd("expected the problem name");
    t.expectWord("contacts", "line 'contacts <number of contacts>'");
    const int nc = static_cast<int>(t.integer("number of contacts", 0, 10'000'000));
    t.expectWord("mu", "then one friction coefficient per contact");
    std::vector<double> mu(nc);
    for (int c = 0; c < nc; ++c) {
      mu[c] = t.number("mu of contact " + std::to_string(c));
      if (mu[c] < 0) t.fail("mu of contact " + std::to_string(c) + " is negative");
    }
    t.expectWord("q", "then 3 numbers per contact");
    Eigen::VectorXd q(3 * nc);
    for (int i = 0; i < 3 * nc; ++i)
      q[i] = t.number("q[" + std::to_string(i) + "] (contact " + std::to_string(i / 3) + ")");
    t.expectWord("W", "line 'W <number of blocks>'");
    const long nb = t.integer("number of W blocks", nc, static_cast<long>(nc) * nc);
    std::vector<MatrixBlockEntry> entries;
    entries.reserve(nb);
    std::vector<bool> hasDiagonal(nc, false);
    long prevI = -1, prevJ = -1;
    for (long k = 0; k < nb; ++k) {
      const std::string rec = "W block record " + std::to_string(k);
      MatrixBlockEntry e;
      e.row = static_cast<int>(t.integer(rec + ": contact index i", 0, nc - 1));
      e.col = static_cast<int>(t.integer(rec + ": contact index j", 0, nc - 1));
      if (e.row < prevI || (e.row == prevI && e.col <= prevJ))
        t.fail(rec + ": blocks must be sorted by (i, j) without duplicates");
      prevI = e.row;
      prevJ = e.col;
      e.values.resize(9);
      for (int v = 0; v < 9; ++v) e.values[v] = t.number(rec + ": value " + std::to_string(v));
      if (e.row == e.col) hasDiagonal[e.row] = true;
      entries.push_back(std::move(e));
    }
    for (int c = 0; c < nc; ++c)
      if (!hasDiagonal[c]) t.fail("W has no diagonal block for contact " + std::to_string(c));
    t.expectWord("end", "after the W records");
    std::string extra;
    if (t.next(extra)) t.fail("unexpected '" + extra + "' after 'end'");
    ContactProblem p = ContactProblem::contacts(
        DelassusOperator::blockSparse(BlockSparseMatrix(std::vector<int>(nc, 3), entries)), q, mu,
        name);
    result.problem = std::move(p);
  } catch (const std::runtime_error& e) {
    result.error = e.what();
    result.problem.reset();
  }
  return result;
}

Fc3dReadResult readFc3dText(const std::string& path) {
  std::ifstream f(path);
  if (!f) {
    Fc3dReadResult r;
    r.error = path + ": cannot open the file (does it exist and is it readable?)";
    return r;
  }
  return parseFc3dText(f, path);
}

namespace {

std::string shortest(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace

void writeVector(const Eigen::VectorXd& v, std::ostream& out, int perLine) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    out << shortest(v[i]) << ((i + 1) % perLine == 0 || i + 1 == v.size() ? "\n" : " ");
}

std::optional<Eigen::VectorXd> readVector(const std::string& path, Eigen::Index size,
                                          std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open the file (does it exist and is it readable?)";
    return std::nullopt;
  }
  Eigen::VectorXd v(size);
  Eigen::Index count = 0;
  try {
    Tokens t(in, path);
    double value = 0.0;
    while (t.nextNumber("number " + std::to_string(count + 1), value)) {
      if (count < size) v[count] = value;
      ++count;
    }
  } catch (const std::runtime_error& e) {  // FILE:LINE: what is wrong
    error = e.what();
    return std::nullopt;
  }
  if (count != size) {
    error = path + ": " + std::to_string(count) + " numbers, expected " + std::to_string(size) +
            " (3 per contact)";
    return std::nullopt;
  }
  return v;
}

std::string writeFc3dText(const ContactProblem& problem, std::ostream& out,
                          const std::string& family) {
  for (const ConstraintBlock& b : problem.blocks)
    if (!b.isContact() || b.anisotropic)
      return "fc3d-text holds isotropic contacts only (found a " +
             std::string(blockKindName(b.kind)) + " block)";
  if (auto bad = problem.validate()) return *bad;
  const int nc = problem.contactCount();
  const BlockSparseMatrix W = problem.W.toBlockSparse(problem.blockSizes());
  if (!family.empty()) out << "# family: " << family << "\n";
  out << "fc3d-text 1\nname " << (problem.name.empty() ? "unnamed" : problem.name) << "\n";
  out << "contacts " << nc << "\nmu\n";
  for (const ConstraintBlock& b : problem.blocks) out << shortest(b.mu) << "\n";
  out << "q\n";
  writeVector(problem.q, out);
  out << "W " << W.nonZeroBlocks() << "\n";
  for (int i = 0; i < W.blockCount(); ++i)
    for (int k = W.rowBegin(i); k < W.rowEnd(i); ++k) {
      out << i << " " << W.blockColumn(k);
      for (int v = 0; v < 9; ++v) out << " " << shortest(W.blockValues(k)[v]);
      out << "\n";
    }
  out << "end\n";
  return {};
}

}  // namespace coulomb::solvers
