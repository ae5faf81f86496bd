#pragma once
// Internal to the URDF loader: the <gazebo> extensions of a URDF (docs/urdf.md, "Gazebo
// extensions"). Gazebo's URDF converter reads a value from the element's `value` attribute, else
// from its text, so <mu1>0.6</mu1> and <mu1 value="0.6"/> mean the same; this reader does the
// same. Nothing here fails a load: robot descriptions carry plugins, sensors and simulator
// settings that Coulomb has no use for. An invalid value is a warning "<file>:<line>: ..." that
// drops that one value; every child that is not used is counted as ignored (UrdfGazeboUse).
#include <coulomb/urdf/UrdfLoader.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

class TiXmlElement;

namespace coulomb::engine::io {

class UrdfGazeboReader {
 public:
  explicit UrdfGazeboReader(std::string source) : source_(std::move(source)) {}

  /// Records one <gazebo> element (a child of <robot>). Its reference may name a link declared
  /// further down the file, so blocks are interpreted in finish().
  void add(const TiXmlElement& block);

  /// Interprets the blocks in file order (a later valid <mu1> for a link replaces an earlier one,
  /// as in Gazebo) once every link and joint name is known; appends the warnings.
  [[nodiscard]] UrdfGazeboUse finish(const std::set<std::string>& links,
                                     const std::set<std::string>& joints,
                                     std::vector<std::string>& warnings) const;

 private:
  struct Child {
    std::string element;
    int line = 0;
    std::optional<std::string> value;  // the `value` attribute, else the text; none if neither
  };
  struct Block {
    std::optional<std::string> reference;  // none: a block of the whole robot
    int line = 0;
    std::vector<Child> children;
  };

  [[nodiscard]] std::string where(const Block& block, const Child& child) const;
  /// The friction coefficient of a <mu1>/<mu2>, or none (with a warning) if it is invalid.
  [[nodiscard]] std::optional<double> coefficient(const Block& block, const Child& child,
                                                  std::vector<std::string>& warnings) const;

  std::string source_;
  std::vector<Block> blocks_;
};

}  // namespace coulomb::engine::io
