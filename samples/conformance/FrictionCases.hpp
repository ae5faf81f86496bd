#pragma once
// The friction cases of docs/scene-specifications.md (A1 sphere_slide, A2 box_incline, B5
// spin_decay, B6 backspin, B7 painleve_rod) with every metric docs/scene-specifications.md defines,
// so a test can compare each one with its discrete floor. The floors are what an exact
// velocity-level step gives at dt 0.01 (docs/scene-specifications.md section 0), recomputed here to
// full precision by the same reduced recurrences docs/scene-specifications.md part C describes (one
// contact: exact clamp; the 4-corner box: exact cone); docs/scene-specifications.md prints them
// rounded.
#include "ConformanceCase.hpp"

#include <string>
#include <utility>
#include <vector>

namespace coulomb::conformance {

/// A friction case's run plus its docs/scene-specifications.md metrics by name ("x_err",
/// "first_Pn", ...).
struct MeasuredCase {
  CaseRun run;
  std::vector<std::pair<std::string, double>> figures;
  /// The figure called `name`; throws CoulombError if the case has none.
  [[nodiscard]] double figure(const std::string& name) const;
};

/// Runs the friction case `name` ("sphere_slide", "box_incline/C_flat_22.5deg", ...).
MeasuredCase measureFrictionCase(const std::string& name, const CaseOptions& options);

/// Discrete floors at dt 0.01 (docs/scene-specifications.md section 0 "discrete floor"; values of
/// docs/scene-specifications.md in [ ]).
namespace floors {
inline constexpr double kSphereSlideXErr = 0.00282138050857794;      // A1 x_err [0.00282138] m
inline constexpr double kInclineStopDistErr = -0.00494179918450564;  // A2 C [-0.0049418] m
inline constexpr double kInclineAcc = 0.921838460990976;      // A2 B g(sin 20 - mu cos 20) m/s^2
inline constexpr double kSpinOmegaHalf = 9.59492371483998;    // B5 omega(0.5) [9.594924] rad/s
inline constexpr double kSpinStop = 0.97;                     // B5 t_stop (step 97) s
inline constexpr double kSpinAngleErr = -0.0999006308497101;  // B5 angle 9.510793 - 9.610694 rad
inline constexpr double kBackspinXMaxErr = -0.00999406123003832;   // B6 [-0.00999] m
inline constexpr double kBackspinReturnErr = -0.0119742488160783;  // B6 [-0.01197] s
inline constexpr double kRodSlidePn = 0.258155876461083;           // B7 mu 1.0: Pn = Pt = mg h / B
inline constexpr double kRodStickPn = 0.377343798826996;           // B7 mu 1.5: [0.3773438] N s
inline constexpr double kRodStickPt = 0.41549539749299;            // B7 mu 1.5: [0.4154954] N s
}  // namespace floors

}  // namespace coulomb::conformance
