#include <coulomb/engine/Sleep.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coulomb::engine {

std::optional<std::string> SleepSettings::validate() const {
  std::ostringstream out;
  if (!std::isfinite(linearSpeed) || linearSpeed < 0.0)
    out << "sleep linear speed must be finite and >= 0 m/s (got " << linearSpeed << ")";
  else if (!std::isfinite(angularSpeed) || angularSpeed < 0.0)
    out << "sleep angular speed must be finite and >= 0 rad/s (got " << angularSpeed << ")";
  else if (!std::isfinite(timeToSleep) || timeToSleep < 0.0)
    out << "sleep time must be finite and >= 0 s (got " << timeToSleep << ")";
  else
    return std::nullopt;
  return out.str();
}

void Sleep::resize(std::size_t n) {
  slowFor_.resize(n, 0.0);
  group_.resize(n, -1);
}

void Sleep::wake(std::size_t index, geometry::BodyState& state) {
  resize(state.size());
  if (index >= state.size() || state.asleep[index] == 0) return;
  const std::int32_t group = group_[index];
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (state.asleep[i] == 0 || group_[i] != group) continue;
    state.asleep[i] = 0;
    group_[i] = -1;
    slowFor_[i] = 0.0;
  }
}

std::size_t Sleep::wakeTouched(const std::vector<geometry::ContactManifold>& manifolds,
                               geometry::BodyState& state, const Eigen::Vector3d& gravity,
                               double h) {
  resize(state.size());
  std::vector<std::uint8_t>& wasAsleep = wasAsleep_;
  wasAsleep.assign(state.asleep.begin(), state.asleep.end());
  auto wakes = [&](std::uint32_t i) { return state.isDynamic(i) || state.isMovingKinematic(i); };
  for (const geometry::ContactManifold& m : manifolds) {
    const std::uint32_t a = m.bodyA.index, b = m.bodyB.index;
    if (m.sensor || a >= state.size() || b >= state.size()) continue;  // sensors never push
    if (state.asleep[a] != 0 && wakes(b)) wake(a, state);
    if (state.asleep[b] != 0 && wakes(a)) wake(b, state);
  }
  std::size_t woken = 0;
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (wasAsleep[i] == 0 || state.asleep[i] != 0) continue;
    state.linearVelocities[i] += h * gravity;  // the v* this step's prediction skipped
    ++woken;
  }
  return woken;
}

void Sleep::update(const std::vector<Island>& islands, geometry::BodyState& state,
                   const SleepSettings& settings, double h) {
  resize(state.size());
  if (!settings.enabled) return;
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!state.isDynamic(i)) continue;
    const bool slow = state.linearVelocities[i].norm() < settings.linearSpeed &&
                      state.angularVelocities[i].norm() < settings.angularSpeed;
    slowFor_[i] = slow ? slowFor_[i] + h : 0.0;
  }
  auto putToSleep = [&](const std::vector<std::int32_t>& bodies) {
    for (const std::int32_t i : bodies)
      if (slowFor_[i] < settings.timeToSleep) return;
    for (const std::int32_t i : bodies) {
      state.asleep[i] = 1;
      group_[i] = bodies.front();
      state.linearVelocities[i].setZero();
      state.angularVelocities[i].setZero();
    }
  };
  std::vector<std::uint8_t> inIsland(state.size(), 0);
  for (const Island& island : islands) {
    for (const std::int32_t i : island.bodies) inIsland[i] = 1;
    putToSleep(island.bodies);
  }
  for (std::size_t i = 0; i < state.size(); ++i)  // free bodies sleep alone
    if (state.isDynamic(i) && inIsland[i] == 0) putToSleep({static_cast<std::int32_t>(i)});
}

std::size_t Sleep::sleepingBodies(const geometry::BodyState& state) const {
  return static_cast<std::size_t>(std::count(state.asleep.begin(), state.asleep.end(), 1));
}

}  // namespace coulomb::engine
