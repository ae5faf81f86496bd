#include <coulomb/io/Snapshot.hpp>
#include <coulomb/io/SnapshotArchive.hpp>

#include <array>
#include <fstream>
#include <iterator>

namespace coulomb::engine::io {

namespace {

constexpr std::array<char, 8> kMagic = {'C', 'L', 'M', 'B', 'S', 'N', 'A', 'P'};
constexpr std::uint32_t kByteOrderMark = 0x01020304u;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;

std::uint64_t fnv1a(std::span<const std::uint8_t> bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return h;
}

template <class Ar>
void transferChoice(Ar& ar, solvers::SolverChoice& choice) {
  ioEnum(ar, choice.mode, solvers::ChoiceMode::Exactly);
  const std::size_t n = ar.length(choice.attempts.size(), 1, "a solver choice");
  if constexpr (Ar::kLoading) choice.attempts.resize(n);
  for (solvers::SolveAttempt& a : choice.attempts) {
    io(ar, a.solver);
    io(ar, a.maxIterations);
    io(ar, a.stallWindow);
    io(ar, a.tolerance);
  }
}

template <class Ar>
void transferPolicy(Ar& ar, solvers::SolvePolicy& p) {
  transferChoice(ar, p.choice);
  io(ar, p.options.tolerance);
  io(ar, p.options.maxIterations);
  io(ar, p.options.timeLimitSeconds);
  io(ar, p.options.useWarmStart);
  io(ar, p.options.recordHistory);
  io(ar, p.options.stallWindow);
  if (ar.version() >= 8)
    io(ar, p.options.sweepPartBlocks);
  else if constexpr (Ar::kLoading)
    p.options.sweepPartBlocks = 0;  // the block order those files were written with
  if (ar.version() >= 9)
    io(ar, p.options.stickingStart);
  else if constexpr (Ar::kLoading)
    p.options.stickingStart = false;  // the starts those files were written with
  if (ar.version() >= 11)
    io(ar, p.options.startSweep);
  else if constexpr (Ar::kLoading)
    p.options.startSweep = false;  // as those files were written
  solvers::ChooserSettings& c = p.chooser;
  io(ar, c.pileNu);
  io(ar, c.newtonMaxUnknowns);
  io(ar, c.pileContactsWithoutDofs);
  io(ar, c.smallActiveContacts);
  io(ar, c.smallTrySweeps);
  io(ar, c.factoredTrySweeps);
  io(ar, c.newtonMassRatio);
  io(ar, c.pileStallSweeps);
  io(ar, p.promotion.enabled);
  io(ar, p.promotion.nearMiss);
  io(ar, p.promotion.iterationCap);
  io(ar, p.promotion.toleranceScale);
  io(ar, p.promotion.minUnknowns);
}

template <class Ar>
void transferOverrides(Ar& ar, std::vector<std::optional<solvers::SolverChoice>>& overrides) {
  const std::size_t n = ar.length(overrides.size(), 1, "the solver overrides");
  if constexpr (Ar::kLoading) overrides.assign(n, std::nullopt);
  for (std::optional<solvers::SolverChoice>& o : overrides) {
    bool present = o.has_value();
    io(ar, present);
    if (present && !o) o.emplace();
    if (present) transferChoice(ar, *o);
  }
}

/// Every field of the settings, in declaration order (WorldSettings.hpp and the structs it holds).
template <class Ar>
void transferSettings(Ar& ar, WorldSettings& s) {
  io(ar, s.gravity);
  io(ar, s.timeStep);
  io(ar, s.defaultDensity);
  io(ar, s.unitQuaternionTolerance);
  transferPolicy(ar, s.solve);
  io(ar, s.assembly.sparseRowLimit);
  io(ar, s.assembly.bodySpace);
  io(ar, s.contact.restitutionThreshold);
  io(ar, s.contact.speculativeContacts);
  ioEnum(ar, s.contact.penetration.method, PenetrationMethod::None);
  io(ar, s.contact.penetration.beta);
  io(ar, s.contact.penetration.slop);
  io(ar, s.contact.penetration.solver);
  io(ar, s.contact.penetration.iterations);
  io(ar, s.contact.penetration.tolerance);
  ioEnum(ar, s.contact.impactLaw, ImpactLaw::Propagating);
  io(ar, s.contact.touchingTolerance);
  io(ar, s.contact.maxImpactSweeps);
  io(ar, s.contact.elasticTurning);
  io(ar, s.collision.speculativeMargin);
  io(ar, s.collision.speculativeSweep);
  io(ar, s.collision.matchDistance);
  io(ar, s.collision.maxMeshContacts);
  io(ar, s.sleep.enabled);
  io(ar, s.sleep.linearSpeed);
  io(ar, s.sleep.angularSpeed);
  io(ar, s.sleep.timeToSleep);
  io(ar, s.quarantine.maxPosition);
  io(ar, s.quarantine.maxLinearSpeed);
  io(ar, s.quarantine.maxAngularSpeed);
  ioEnum(ar, s.jointStabilization.method, joints::StabilizationMethod::None);
  io(ar, s.jointStabilization.baumgarte.beta);
  io(ar, s.jointStabilization.baumgarte.slop);
  io(ar, s.jointStabilization.predictedState.iterations);
  io(ar, s.jointStabilization.predictedState.tolerance);
  if (ar.version() >= 10)
    ioEnum(ar, s.jointStabilization.predictedState.energy, joints::EnergyTarget::Exact);
  else if constexpr (Ar::kLoading)
    s.jointStabilization.predictedState.energy = joints::EnergyTarget::None;  // as written
  if (ar.version() >= 7)
    ioEnum(ar, s.treeIntegrator, TreeIntegrator::SemiImplicitEuler);
  else if constexpr (Ar::kLoading)
    s.treeIntegrator = TreeIntegrator::SemiImplicitEuler;
}

template <class Ar>
void transferBodyState(Ar& ar, geometry::BodyState& b) {
  io(ar, b.poses);
  io(ar, b.linearVelocities);
  io(ar, b.angularVelocities);
  io(ar, b.inverseMasses);
  io(ar, b.bodyInverseInertias);
  io(ar, b.worldInverseInertias);
  io(ar, b.principalMoments);
  io(ar, b.principalFrames);
  for (geometry::MotionType& type : b.motionTypes) ioEnum(ar, type, geometry::MotionType::Dynamic);
  io(ar, b.asleep);
  io(ar, b.forces);
  io(ar, b.torques);
}

template <class Ar>
void transferManifolds(Ar& ar, std::vector<geometry::ContactManifold>& manifolds) {
  constexpr std::size_t kMinBytes = 100;  // far below one stored manifold
  const std::size_t n = ar.length(manifolds.size(), kMinBytes, "the contact cache");
  if constexpr (Ar::kLoading) manifolds.assign(n, {});
  for (geometry::ContactManifold& m : manifolds) {
    io(ar, m.colliderA);
    io(ar, m.colliderB);
    io(ar, m.bodyA);
    io(ar, m.bodyB);
    io(ar, m.normal);
    io(ar, m.tangent1);
    io(ar, m.tangent2);
    io(ar, m.friction);
    io(ar, m.restitution);
    io(ar, m.pointCount);
    if constexpr (Ar::kLoading)
      if (m.pointCount < 0 || m.pointCount > geometry::ContactManifold::kMaxPoints)
        ar.fail("corrupt: a manifold has " + std::to_string(m.pointCount) + " points");
    for (geometry::ContactPoint& p : m.points) {  // all 4, active or not: bit for bit
      io(ar, p.position);
      io(ar, p.depth);
      io(ar, p.featureId);
      io(ar, p.localA);
      io(ar, p.localB);
      io(ar, p.normalImpulse);
      io(ar, p.tangentImpulse);
      io(ar, p.warmStarted);
      io(ar, p.solvedNormal);
      io(ar, p.solvedMomentA);
      io(ar, p.solvedMomentB);
      io(ar, p.solvedNormalVelocity);
    }
  }
}

}  // namespace

/// The one description of the format, for both directions (a friend of the World and its stages).
struct SnapshotAccess {
  /// Every per-slot array read from the data has one entry per body slot (lazily sized ones, at
  /// most one).
  static void checkSizes(const SnapshotReader& ar, const World& w) {
    const geometry::BodyState& b = w.state_;
    const std::size_t n = b.alive.size();
    for (const std::size_t size :
         {b.poses.size(), b.linearVelocities.size(), b.angularVelocities.size(),
          b.inverseMasses.size(), b.bodyInverseInertias.size(), b.worldInverseInertias.size(),
          b.principalMoments.size(), b.principalFrames.size(), b.motionTypes.size(),
          b.asleep.size(), b.forces.size(), b.torques.size()})
      if (size != n)
        ar.fail("corrupt: a body array has " + std::to_string(size) + " entries for " +
                std::to_string(n) + " slots");
    if (w.quarantine_.flags_.size() > n) ar.fail("corrupt: quarantine flags");
  }

  template <class Ar>
  static void transfer(Ar& ar, World& w) {
    // Structure: must be the same World (see Snapshot.hpp).
    ar.expect(static_cast<std::uint64_t>(w.state_.size()), "the number of body slots");
    for (std::size_t i = 0; i < w.state_.size(); ++i) {
      ar.expect(w.state_.alive[i], "a body slot's liveness");
      ar.expect(w.generations_[i], "a body slot's generation");
      ar.expect(
          fnv1a({reinterpret_cast<const std::uint8_t*>(w.names_[i].data()), w.names_[i].size()}),
          "a body's name (hash)");
    }
    ar.expect(static_cast<std::uint64_t>(w.colliders_.size()), "the number of colliders");
    for (const geometry::Collider& c : w.colliders_) {
      ar.expect(c.id.index, "a collider id");
      ar.expect(c.body.index, "a collider's body");
    }
    ar.expect(w.colliderCounter_, "the collider counter");
    ar.expect(static_cast<std::uint64_t>(w.joints_.records_.size()), "the number of joint slots");
    for (const JointStage::Record& r : w.joints_.records_) {
      ar.expect(r.alive, "a joint slot's liveness");
      ar.expect(r.generation, "a joint slot's generation");
    }
    ar.expect(static_cast<std::uint64_t>(w.articulations_.records_.size()),
              "the number of articulations");
    for (const ArticulationStage::Record& r : w.articulations_.records_) {
      if (ar.version() >= 6) {  // format 5 had no removable articulations
        ar.expect(r.alive, "an articulation slot's liveness");
        ar.expect(r.generation, "an articulation slot's generation");
      }
      ar.expect(static_cast<std::int64_t>(r.q.size()), "an articulation's nq");
      ar.expect(static_cast<std::int64_t>(r.qd.size()), "an articulation's nv");
      ar.expect(static_cast<std::uint64_t>(r.links.size()), "an articulation's link count");
    }
    // State.
    io(ar, w.time_);
    io(ar, w.stepCount_);
    if constexpr (Ar::kLoading) {
      WorldSettings settings = w.settings_;
      transferSettings(ar, settings);
      if (auto bad = settings.validate()) ar.fail("corrupt settings: " + *bad);
      if (auto bad = settings.solve.validate(&w.registry_))
        ar.fail("settings this world cannot use: " + *bad);
      const auto& c = w.collision_.settings();
      if (settings.collision.speculativeMargin != c.speculativeMargin ||
          settings.collision.speculativeSweep != c.speculativeSweep ||
          settings.collision.matchDistance != c.matchDistance ||
          settings.collision.maxMeshContacts != c.maxMeshContacts)
        ar.fail(
            "does not match this world: its collision settings differ (they are fixed when "
            "the World is built)");
      w.settings_ = std::move(settings);
    } else {
      transferSettings(ar, w.settings_);
    }
    transferOverrides(ar, w.solverOverrides_);
    if constexpr (Ar::kLoading)
      if (w.solverOverrides_.size() != w.state_.size()) ar.fail("corrupt: solver overrides");
    io(ar, w.promotion_.names());
    if constexpr (Ar::kLoading)
      if (w.promotion_.names().size() != w.state_.size()) ar.fail("corrupt: solver promotions");
    transferBodyState(ar, w.state_);
    io(ar, w.quarantine_.flags_);
    if constexpr (Ar::kLoading) checkSizes(ar, w);
    if constexpr (Ar::kLoading) {
      std::vector<geometry::ContactManifold> manifolds;
      transferManifolds(ar, manifolds);
      w.collision_.cache().restore(std::move(manifolds));
    } else {
      transferManifolds(ar, w.collision_.cache().manifolds());
    }
    io(ar, w.sleep_.slowFor_);
    io(ar, w.sleep_.group_);
    if (ar.version() < 6) {  // format 5 had no touching pairs
      if constexpr (Ar::kLoading) w.events_.touching_.clear();
    } else {  // the pairs touching after the last step: the next step's Begin/Persist/End
      std::vector<ContactEvents::Touch>& touching = w.events_.touching_;
      const std::size_t n = ar.length(touching.size(), 20, "the touching pairs");
      if constexpr (Ar::kLoading) touching.assign(n, {});
      for (ContactEvents::Touch& t : touching) {
        io(ar, t.colliderA);
        io(ar, t.colliderB);
        io(ar, t.bodyA);
        io(ar, t.bodyB);
        io(ar, t.sensor);
      }
    }
    for (JointStage::Record& r : w.joints_.records_) {
      io(ar, r.broken);
      io(ar, r.warmStarts);
      io(ar, r.impulseOnB);
      io(ar, r.armB);
      io(ar, r.reaction.force);
      io(ar, r.reaction.torque);
    }
    for (ArticulationStage::Record& r : w.articulations_.records_) {
      if (!r.alive) continue;  // removed: nothing to keep
      io(ar, r.q);
      io(ar, r.qd);
      io(ar, r.tau);
      io(ar, r.linkPoses);
      io(ar, r.closureWarm);
      io(ar, r.lowerWarm);
      io(ar, r.upperWarm);
      ar.expect(static_cast<std::uint64_t>(r.motors.size()), "an articulation's motor count");
      for (JointMotorDesc& m : r.motors) io(ar, m.target);
      io(ar, r.motorWarm);
      io(ar, r.couplingWarm);
      io(ar, r.frictionWarm);
      if constexpr (Ar::kLoading) {
        const auto nq = static_cast<std::size_t>(r.model->nq());
        const auto nv = static_cast<std::size_t>(r.model->nv());
        if (static_cast<std::size_t>(r.q.size()) != nq ||
            static_cast<std::size_t>(r.qd.size()) != nv ||
            static_cast<std::size_t>(r.tau.size()) != nv || r.linkPoses.size() != r.links.size() ||
            r.frictionWarm.size() != r.links.size())
          ar.fail("corrupt: an articulation's state has the wrong size");
      }
    }
  }
};

std::vector<std::uint8_t> saveSnapshot(const World& world) {
  SnapshotWriter payload;
  // The writer only reads; transfer() takes a non-const World so that one template serves both
  // directions.
  SnapshotAccess::transfer(payload, const_cast<World&>(world));
  const std::vector<std::uint8_t>& body = payload.bytes();
  SnapshotWriter out;
  out.raw(kMagic.data(), kMagic.size());
  out.raw(&kSnapshotVersion, sizeof kSnapshotVersion);
  out.raw(&kByteOrderMark, sizeof kByteOrderMark);
  const auto size = static_cast<std::uint64_t>(body.size());
  const std::uint64_t checksum = fnv1a(body);
  out.raw(&size, sizeof size);
  out.raw(&checksum, sizeof checksum);
  out.raw(body.data(), body.size());
  return std::move(out.bytes());
}

namespace {
void restoreChecked(World& world, std::span<const std::uint8_t> bytes, const std::string& source) {
  SnapshotReader header(bytes, source);
  if (bytes.size() < kHeaderBytes)
    header.fail("not a Coulomb snapshot (" + std::to_string(bytes.size()) +
                " bytes, shorter than the header)");
  std::array<char, 8> magic{};
  header.raw(magic.data(), magic.size());
  if (magic != kMagic) header.fail("not a Coulomb snapshot (bad magic)");
  std::uint32_t version = 0, mark = 0;
  std::uint64_t size = 0, checksum = 0;
  header.raw(&version, sizeof version);
  header.raw(&mark, sizeof mark);
  header.raw(&size, sizeof size);
  header.raw(&checksum, sizeof checksum);
  if (version < kOldestReadableVersion || version > kSnapshotVersion)
    header.fail("format version " + std::to_string(version) + ", this build reads versions " +
                std::to_string(kOldestReadableVersion) + " to " + std::to_string(kSnapshotVersion));
  if (mark != kByteOrderMark) header.fail("written on a machine of another byte order");
  if (size != header.remaining())
    header.fail("truncated or padded: the header announces " + std::to_string(size) +
                " payload bytes, the data holds " + std::to_string(header.remaining()));
  const std::span<const std::uint8_t> body = bytes.subspan(kHeaderBytes);
  if (fnv1a(body) != checksum) header.fail("corrupt (checksum mismatch)");
  SnapshotReader reader(body, source, version);
  SnapshotAccess::transfer(reader, world);
  if (reader.remaining() != 0)
    reader.fail(std::to_string(reader.remaining()) + " bytes left over after the state");
}
}  // namespace

void restoreSnapshot(World& world, std::span<const std::uint8_t> bytes, const std::string& source) {
  // Checks that need the World (structure, sizes) run while reading; on any failure the World
  // gets its own state back from a snapshot taken first, which cannot fail.
  const std::vector<std::uint8_t> backup = saveSnapshot(world);
  try {
    restoreChecked(world, bytes, source);
  } catch (const CoulombError&) {
    restoreChecked(world, backup, "backup");
    throw;
  }
}

void saveSnapshotFile(const World& world, const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = saveSnapshot(world);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
  if (!out) throw CoulombError("snapshot '" + path.string() + "': cannot write the file");
}

void loadSnapshotFile(World& world, const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CoulombError("snapshot '" + path.string() + "': cannot open the file");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  restoreSnapshot(world, bytes, path.string());
}

}  // namespace coulomb::engine::io
