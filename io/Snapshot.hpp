#pragma once
// Snapshots: the whole dynamic state of a World in a versioned binary blob, so that a run can be
// continued later (or elsewhere) bit for bit (issue 13 item 3; docs/reliability.md).
//
// What is saved: every body slot's state (pose, velocities, inverse masses and inertias, motion
// type, sleep flag, pending forces), the quarantine flags, the settings (all of them), the
// solver overrides and promotions, the contact cache (manifolds with their warm-start impulses),
// the sleep timers, every joint's broken flag, warm starts and last reaction, every articulation's
// q, qd, pending joint forces, link poses, motor targets and warm starts, the step counter and
// time.
//
// What is not saved: the *structure* (shapes, colliders, masses as described, joint definitions,
// articulation models). A snapshot is restored into a World built from the same scene (same
// bodies, colliders, joints and articulations created in the same order, e.g. by
// engine::io::buildWorld on the same Scene); the restore checks this structure (slot count,
// names, generations, collider ids and owners, joint and articulation counts and sizes) and
// throws a CoulombError naming the first difference. The problem observer and custom solvers
// registered in solverRegistry() are not state and are left as they are.
//
// File layout: "CLMBSNAP", format version (uint32), byte-order mark (uint32), payload size
// (uint64), FNV-1a 64 checksum of the payload (uint64), payload. A bad magic, another version,
// another byte order, a truncated file, a wrong checksum or a mismatched world gives a
// CoulombError naming the file; the World is then left exactly as it was.
#include <coulomb/engine/World.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace coulomb::engine::io {

// 2: collision.speculativeSweep; 3: contact.elasticTurning and the contact points' solved rows;
// 4: promoteFallbacks and the solver promotions (engine/SolverPromotion); 5: the typed solve
// policy (WorldSettings::solve, per-body solver choices), assembly and penetration solver; 6: the
// touching pairs of the contact events (engine/ContactEvents), articulation slots' liveness and
// generation (removable articulations); 7: WorldSettings::treeIntegrator (older files restore as
// SemiImplicitEuler, the integrator they were written with); 8: SolverOptions::
// sweepPartBlocks (older files restore with 0, the block order they were written with); 9:
// SolverOptions::stickingStart (older files restore with it off, as they were written); 10: the
// predicted-state energy target (older files restore with none); 11: SolverOptions::startSweep
// (older files restore with it off).
inline constexpr std::uint32_t kSnapshotVersion = 11;
/// Version 5 files still restore (their touching pairs are empty: pairs touching when the file
/// was written get a Begin event in the first step after the restore).
inline constexpr std::uint32_t kOldestReadableVersion = 5;

/// The snapshot of `world` as bytes (header included).
[[nodiscard]] std::vector<std::uint8_t> saveSnapshot(const World& world);
/// Restores `bytes` into `world`; `source` names the data in error messages (a file name).
/// Throws CoulombError on a bad snapshot or a World of another structure; `world` is unchanged.
void restoreSnapshot(World& world, std::span<const std::uint8_t> bytes,
                     const std::string& source = "<memory>");

/// saveSnapshot into a file; CoulombError naming the file if it cannot be written.
void saveSnapshotFile(const World& world, const std::filesystem::path& path);
/// restoreSnapshot from a file; CoulombError naming the file if it cannot be read or is bad.
void loadSnapshotFile(World& world, const std::filesystem::path& path);

}  // namespace coulomb::engine::io
