#pragma once
// Checked reading of a JSON document for the loaders in io (the only folder that sees
// nlohmann-json; this header is internal to it). Every accessor knows its JSON path
// ("bodies[3].shapes[0].radius") and throws CoulombError "<source>: <path>: <problem>".
#include <coulomb/engine/CoulombError.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine::io {

/// Levenshtein distance (insert, delete, substitute: cost 1), for "did you mean" hints.
std::size_t editDistance(const std::string& a, const std::string& b);
/// The candidate nearest to `word` if it is close enough to be a plausible typo, else nullopt.
std::optional<std::string> nearestName(const std::string& word,
                                       const std::vector<std::string>& candidates);

class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string source, std::string path)
      : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const nlohmann::json& raw() const { return *value_; }
  [[noreturn]] void fail(const std::string& problem) const;

  /// Errors on any key not in `known`, suggesting the nearest known key.
  void allowOnly(std::initializer_list<const char*> known) const;
  [[nodiscard]] bool has(const char* key) const;
  [[nodiscard]] JsonNode child(const char* key) const;        // must exist
  [[nodiscard]] JsonNode element(std::size_t index) const;    // of an array
  [[nodiscard]] std::size_t arraySize() const;                // must be an array
  [[nodiscard]] std::vector<std::string> objectKeys() const;  // must be an object, sorted

  [[nodiscard]] double number() const;  // finite
  [[nodiscard]] bool boolean() const;   // true or false
  [[nodiscard]] double positiveNumber() const;
  [[nodiscard]] std::uint64_t unsignedInteger() const;
  [[nodiscard]] std::string string() const;
  [[nodiscard]] Eigen::Vector3d vector3() const;  // [x, y, z], finite
  [[nodiscard]] Eigen::Vector3i index3() const;   // [i, j, k], non-negative integers

  // Optional members with defaults.
  [[nodiscard]] double number(const char* key, double fallback) const;
  [[nodiscard]] Eigen::Vector3d vector3(const char* key, const Eigen::Vector3d& fallback) const;
  [[nodiscard]] std::string string(const char* key, const std::string& fallback) const;

 private:
  [[nodiscard]] std::string typeName() const;
  const nlohmann::json* value_;
  std::string source_;
  std::string path_;
};

/// An orientation: a unit quaternion [w, x, y, z] (norm within 1e-6, then normalised) or
/// {"axis": [x, y, z], "angle": radians}. Errors name the JSON path.
Eigen::Quaterniond parseOrientation(const JsonNode& node);

}  // namespace coulomb::engine::io
