#pragma once
// "a,b,c" -> {"a", "b", "c"}, empty items dropped: the list arguments (--solvers, --cases,
// --scenes) of the CLI and the benchmark programs.
#include <sstream>
#include <string>
#include <vector>

namespace coulomb::samples {

inline std::vector<std::string> splitCommaList(const std::string& text) {
  std::vector<std::string> items;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

}  // namespace coulomb::samples
