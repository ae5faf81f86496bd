// Compiled against the installed headers and libraries only.
#include <coulomb/geometry/Shape.hpp>

#include <cstdio>

int main() {
  const coulomb::geometry::Shape box = coulomb::geometry::Box{};
  if (coulomb::geometry::validateShape(box).has_value()) return 1;
  std::printf("coulomb consumer ok: %s\n", coulomb::geometry::shapeKindName(box));
  return 0;
}
