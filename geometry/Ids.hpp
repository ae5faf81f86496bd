#pragma once
// Typed handles with a generation counter: an id names a slot and the generation of the object
// that lived there when the id was handed out, so a stale id (object removed, slot reused) is
// detected instead of silently addressing another object (docs/architecture.md golden rule 9).
#include <compare>
#include <cstdint>
#include <functional>

namespace coulomb::geometry {

template <class Tag>
struct TypedId {
  static constexpr std::uint32_t kInvalid = 0xffffffffu;
  std::uint32_t index = kInvalid;
  std::uint32_t generation = 0;

  [[nodiscard]] constexpr bool valid() const { return index != kInvalid; }
  constexpr auto operator<=>(const TypedId&) const = default;
};

struct BodyTag {};
struct ColliderTag {};
struct JointTag {};
struct ArticulationTag {};

using BodyId = TypedId<BodyTag>;
using ColliderId = TypedId<ColliderTag>;
using JointId = TypedId<JointTag>;
using ArticulationId = TypedId<ArticulationTag>;

}  // namespace coulomb::geometry

template <class Tag>
struct std::hash<coulomb::geometry::TypedId<Tag>> {
  std::size_t operator()(const coulomb::geometry::TypedId<Tag>& id) const noexcept {
    return (static_cast<std::size_t>(id.generation) << 32) | id.index;
  }
};
