// <gazebo> extensions of a URDF: friction used, everything else counted as ignored
// (UrdfGazebo.hpp, docs/urdf.md "Gazebo extensions").
#include <coulomb/urdf/UrdfGazebo.hpp>

#include <tinyxml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace coulomb::engine::io {
namespace {

constexpr std::size_t kListed = 12;  // names in one grouped warning, as the loader's lists

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string shortest(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Gazebo's <turnGravityOff>true</turnGravityOff> and <gravity>false</gravity> switch gravity
/// off for one link; Coulomb cannot, and the robot then moves differently from Gazebo.
bool switchesGravityOff(const std::string& element, const std::string& value) {
  const bool yes = value == "true" || value == "1";
  const bool no = value == "false" || value == "0";
  return (element == "turnGravityOff" && yes) || (element == "gravity" && no);
}

}  // namespace

void UrdfGazeboReader::add(const TiXmlElement& element) {
  Block block;
  block.line = element.Row();
  if (const char* reference = element.Attribute("reference")) block.reference = reference;
  for (const TiXmlElement* c = element.FirstChildElement(); c != nullptr;
       c = c->NextSiblingElement()) {
    Child child{c->Value(), c->Row(), std::nullopt};
    if (const char* value = c->Attribute("value"))  // Gazebo: the attribute first, then the text
      child.value = trimmed(value);
    else if (const char* text = c->GetText())
      child.value = trimmed(text);
    block.children.push_back(std::move(child));
  }
  blocks_.push_back(std::move(block));
}

std::string UrdfGazeboReader::where(const Block& block, const Child& child) const {
  return source_ + ":" + std::to_string(child.line) + ": <gazebo reference=\"" +
         block.reference.value_or("") + "\"> <" + child.element + ">: ";
}

std::optional<double> UrdfGazeboReader::coefficient(const Block& block, const Child& child,
                                                    std::vector<std::string>& warnings) const {
  const std::string dropped = "; this value is dropped";
  if (!child.value || child.value->empty()) {
    warnings.push_back(where(block, child) + "no value (write <" + child.element + ">0.8</" +
                       child.element + "> or <" + child.element + " value=\"0.8\"/>)" + dropped);
    return std::nullopt;
  }
  const std::string& text = *child.value;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') {
    warnings.push_back(where(block, child) + "'" + text + "' is not a number" + dropped);
    return std::nullopt;
  }
  if (!std::isfinite(value) || errno == ERANGE) {
    warnings.push_back(where(block, child) + "'" + text + "' is not a finite number" + dropped);
    return std::nullopt;
  }
  if (value < 0.0) {
    warnings.push_back(where(block, child) + text +
                       " is negative (a friction coefficient is >= 0)" + dropped);
    return std::nullopt;
  }
  return value;
}

UrdfGazeboUse UrdfGazeboReader::finish(const std::set<std::string>& links,
                                       const std::set<std::string>& joints,
                                       std::vector<std::string>& warnings) const {
  UrdfGazeboUse use;
  use.blocks = static_cast<int>(blocks_.size());
  struct Mu2 {
    const Block* block;
    const Child* child;
    double value;
  };
  std::vector<Mu2> mu2;                 // judged against the link's final mu1
  std::vector<std::string> gravityOff;  // "link (line n)", one warning for all (pr2: 42 links)
  for (const Block& block : blocks_) {
    const bool ofLink = block.reference && links.count(*block.reference) != 0;
    if (block.reference && !ofLink && joints.count(*block.reference) == 0)
      warnings.push_back(source_ + ":" + std::to_string(block.line) + ": <gazebo reference=\"" +
                         *block.reference + "\">: no link or joint is named '" + *block.reference +
                         "'; the block is ignored");
    for (const Child& child : block.children) {
      const bool friction = child.element == "mu1" || child.element == "mu2";
      if (!ofLink || !friction) {
        ++use.ignored[child.element];
        if (ofLink && child.value && switchesGravityOff(child.element, *child.value))
          gravityOff.push_back(*block.reference + " (line " + std::to_string(child.line) + ")");
        continue;
      }
      const std::optional<double> value = coefficient(block, child, warnings);
      if (!value) {
        ++use.ignored[child.element];
      } else if (child.element == "mu1") {
        use.friction[*block.reference] = *value;
        ++use.used["mu1"];
      } else {
        mu2.push_back({&block, &child, *value});
      }
    }
  }
  if (!gravityOff.empty()) {
    std::string list;
    for (std::size_t i = 0; i < gravityOff.size() && i < kListed; ++i)
      list += (i > 0 ? ", " : "") + gravityOff[i];
    if (gravityOff.size() > kListed)
      list += ", ... (" + std::to_string(gravityOff.size()) + " in all)";
    warnings.push_back(source_ +
                       ": <gazebo> switches gravity off (turnGravityOff true or gravity "
                       "false) for " +
                       std::to_string(gravityOff.size()) +
                       " link(s); ignored, Coulomb applies gravity to every body: " + list);
  }
  // Coulomb's friction cone is isotropic: mu2 (Gazebo's second friction direction) can only
  // agree with mu1.
  for (const Mu2& m : mu2) {
    const auto mu1 = use.friction.find(*m.block->reference);
    if (mu1 != use.friction.end() && mu1->second == m.value) {
      ++use.used["mu2"];
      continue;
    }
    ++use.ignored["mu2"];
    warnings.push_back(where(*m.block, *m.child) +
                       (mu1 == use.friction.end()
                            ? std::string("no <mu1> for this link; ignored (Coulomb's friction "
                                          "cone is isotropic and takes its coefficient from mu1)")
                            : shortest(m.value) + " differs from <mu1> " + shortest(mu1->second) +
                                  "; ignored (Coulomb's friction cone is isotropic: the link's "
                                  "friction is mu1)"));
  }
  return use;
}

}  // namespace coulomb::engine::io
