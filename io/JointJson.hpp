#pragma once
// The "joints" section of a JSON scene and the world's default joint stabilization
// (docs/scene-format.md "Joints"). Internal to io (it reads JsonNode).
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/io/JsonReader.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/joints/Stabilization.hpp>

#include <vector>

namespace coulomb::engine::io {

/// "baumgarte" | "predicted_state" | "none", or {"method", "beta", "slop", "iterations",
/// "tolerance"}; absent keys keep the values of `base`.
joints::Stabilization parseStabilization(const JsonNode& node, joints::Stabilization base);

/// One joint of the "joints" array. Ends are named bodies of `bodies` ("world" or absent = the
/// world); world-coordinate frames are moved into the bodies' reference frames using their
/// initial poses. A per-joint "stabilization" starts from `worldPolicy`.
SceneJoint parseJoint(const JsonNode& node, const std::vector<BodyDesc>& bodies,
                      const joints::Stabilization& worldPolicy);

}  // namespace coulomb::engine::io
