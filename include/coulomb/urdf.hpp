#pragma once
// Component coulomb::urdf (urdfdom; docs/urdf.md): URDF robots as articulations (reduced
// coordinates) or as bodies and joints (maximal coordinates).
#include <coulomb/urdf/UrdfLoader.hpp>
#include <coulomb/urdf/UrdfMaximal.hpp>
#include <coulomb/world.hpp>

namespace coulomb {

using engine::io::createMaximal;       // (World&, UrdfMaximal) -> the ids of its bodies and joints
using engine::io::loadUrdfFile;        // file -> UrdfModel (errors name file:line)
using engine::io::parseUrdf;           // text -> UrdfModel
using engine::io::toArticulationDesc;  // UrdfModel -> ArticulationDesc (World::createArticulation)
using engine::io::toMaximal;           // UrdfModel -> bodies and joints
using engine::io::UrdfBase;
using engine::io::UrdfModel;
using engine::io::UrdfOptions;

}  // namespace coulomb
