#pragma once
// Coulomb's public API, component coulomb::core (docs/embedding.md): the World and everything it
// takes and gives, named in namespace coulomb. The headers these names come from are internal
// (installed under include/coulomb/detail/): they may change between versions; these names stay.
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/ContactEvents.hpp>
#include <coulomb/engine/ContactHooks.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/engine/WorldSettings.hpp>

namespace coulomb {

// The world and its reports.
using engine::CoulombError;  // every refusal of bad input (a std::runtime_error)
using engine::IslandReport;
using engine::StepReport;
using engine::World;
using engine::WorldSettings;

// What bodies, joints and trees are made of.
using engine::ArticulationDesc;
using engine::ArticulationLinkDesc;
using engine::BodyDesc;
using engine::JointDesc;
using engine::JointMotorDesc;
using engine::JointMotorMode;
using engine::JointReaction;
using engine::ShapeDesc;
using geometry::Box;
using geometry::Capsule;
using geometry::Collider;
using geometry::CollisionFilter;
using geometry::ConvexHull;  // with its faces (coulomb::makeConvexHull builds them from points)
using geometry::Cylinder;
using geometry::Material;
using geometry::MotionType;
using geometry::Plane;
using geometry::Pose;
using geometry::Shape;
using geometry::SpatialInertia;
using geometry::Sphere;
using geometry::TriangleMesh;
using joints::JointType;

// Handles: generation-checked, refused once their object is removed.
using geometry::ArticulationId;
using geometry::BodyId;
using geometry::ColliderId;
using geometry::JointId;

// Contact events and hooks.
using engine::ContactEvent;
using engine::ContactEventType;
using engine::ContactFilter;
using engine::ContactModification;
using engine::PreSolveHook;
using engine::SensorEvent;

// Solvers: which ones an island gets.
using solvers::SolvePolicy;
using solvers::SolverChoice;
using solvers::solverChoice;  // "auto", "pgs", "ac_newton!", "bgs,ac_newton", ...

}  // namespace coulomb
