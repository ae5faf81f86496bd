#include <coulomb/io/JsonReader.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coulomb::engine::io {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> nearestName(const std::string& word,
                                       const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t bestDistance = 0;
  for (const std::string& candidate : candidates) {
    const std::size_t d = editDistance(word, candidate);
    if (!best || d < bestDistance) {
      best = candidate;
      bestDistance = d;
    }
  }
  // A plausible typo: at most a third of the longer word wrong (and at least 2 edits allowed).
  const std::size_t allowed = std::max<std::size_t>(2, std::max(word.size(), std::size_t{3}) / 3);
  if (best && bestDistance <= allowed) return best;
  return std::nullopt;
}

void JsonNode::fail(const std::string& problem) const {
  throw CoulombError(source_ + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": " +
                     problem);
}

std::string JsonNode::typeName() const {
  return value_->type_name();
}

void JsonNode::allowOnly(std::initializer_list<const char*> known) const {
  if (!value_->is_object()) fail("expected an object, got " + typeName());
  const std::vector<std::string> names(known.begin(), known.end());
  for (const auto& [key, unused] : value_->items()) {
    if (std::find(names.begin(), names.end(), key) != names.end()) continue;
    std::string message = "unknown key '" + key + "'";
    if (auto suggestion = nearestName(key, names))
      message += "; did you mean '" + *suggestion + "'?";
    else {
      message += "; known keys:";
      for (const auto& n : names) message += " " + n;
    }
    JsonNode(*value_, source_, path_.empty() ? key : path_ + "." + key).fail(message);
  }
}

bool JsonNode::has(const char* key) const {
  return value_->is_object() && value_->contains(key);
}

JsonNode JsonNode::child(const char* key) const {
  if (!value_->is_object()) fail("expected an object, got " + typeName());
  const std::string childPath = path_.empty() ? key : path_ + "." + key;
  if (!value_->contains(key)) JsonNode(*value_, source_, childPath).fail("missing (required)");
  return {value_->at(key), source_, childPath};
}

JsonNode JsonNode::element(std::size_t index) const {
  return {value_->at(index), source_, path_ + "[" + std::to_string(index) + "]"};
}

std::size_t JsonNode::arraySize() const {
  if (!value_->is_array()) fail("expected an array, got " + typeName());
  return value_->size();
}

std::vector<std::string> JsonNode::objectKeys() const {
  if (!value_->is_object()) fail("expected an object, got " + typeName());
  std::vector<std::string> keys;
  for (const auto& [key, unused] : value_->items()) keys.push_back(key);
  return keys;  // nlohmann's default object is a std::map: already sorted
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false");
  return value_->get<bool>();
}

double JsonNode::number() const {
  if (!value_->is_number()) fail("expected a number, got " + typeName());
  const double x = value_->get<double>();
  if (!std::isfinite(x)) fail("must be finite");
  return x;
}

double JsonNode::positiveNumber() const {
  const double x = number();
  if (x <= 0.0) {
    std::ostringstream out;
    out << "must be > 0 (got " << x << ")";
    fail(out.str());
  }
  return x;
}

std::uint64_t JsonNode::unsignedInteger() const {
  if (!value_->is_number_integer() ||
      (value_->is_number_integer() && !value_->is_number_unsigned()))
    fail("expected a non-negative integer, got " +
         (value_->is_number() ? value_->dump() : typeName()));
  return value_->get<std::uint64_t>();
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("expected a string, got " + typeName());
  return value_->get<std::string>();
}

Eigen::Vector3d JsonNode::vector3() const {
  if (!value_->is_array() || value_->size() != 3)
    fail("expected an array of 3 numbers [x, y, z], got " + value_->dump());
  return {element(0).number(), element(1).number(), element(2).number()};
}

Eigen::Vector3i JsonNode::index3() const {
  if (!value_->is_array() || value_->size() != 3)
    fail("expected an array of 3 vertex indices, got " + value_->dump());
  Eigen::Vector3i v;
  for (int k = 0; k < 3; ++k) {
    const std::uint64_t i = element(static_cast<std::size_t>(k)).unsignedInteger();
    if (i > 0x7fffffffu) element(static_cast<std::size_t>(k)).fail("vertex index too large");
    v[k] = static_cast<int>(i);
  }
  return v;
}

double JsonNode::number(const char* key, double fallback) const {
  return has(key) ? child(key).number() : fallback;
}

Eigen::Vector3d JsonNode::vector3(const char* key, const Eigen::Vector3d& fallback) const {
  return has(key) ? child(key).vector3() : fallback;
}

std::string JsonNode::string(const char* key, const std::string& fallback) const {
  return has(key) ? child(key).string() : fallback;
}

Eigen::Quaterniond parseOrientation(const JsonNode& node) {
  if (node.raw().is_object()) {
    node.allowOnly({"axis", "angle"});
    const Eigen::Vector3d axis = node.child("axis").vector3();
    if (axis.norm() < 1e-12) node.child("axis").fail("must be non-zero");
    return Eigen::Quaterniond(Eigen::AngleAxisd(node.child("angle").number(), axis.normalized()));
  }
  if (!node.raw().is_array() || node.raw().size() != 4)
    node.fail("expected a quaternion [w, x, y, z] or {\"axis\": [x, y, z], \"angle\": radians}");
  const Eigen::Quaterniond q(node.element(0).number(), node.element(1).number(),
                             node.element(2).number(), node.element(3).number());
  if (std::abs(q.norm() - 1.0) > 1e-6) {
    std::ostringstream out;
    out << "quaternion [w, x, y, z] must have unit norm (norm " << q.norm() << ")";
    node.fail(out.str());
  }
  return q.normalized();
}

}  // namespace coulomb::engine::io
