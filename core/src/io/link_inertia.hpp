#pragma once
// A URDF link's <inertial> as the loader takes it under the inertia policy (accept, strict,
// repair): the checks on mass and rotational inertia, what counts as round-off of zero,
// and the smallest repair that makes an inertia physical.
#include <string>
#include <vector>

#include "achd/spatial.hpp"
#include "achd/urdf.hpp"

namespace achd {

// The six numbers of <inertia> (ixx, ixy, ixz, iyy, iyz, izz) and the mass as written,
// with the round-off of each as written in the file: half a unit of its last digit
// ("0.000001" -> 5e-7, "1.5e-05" -> 5e-7), 0 for an exact zero or an integer.
struct WrittenInertia {
  double mass = 0;
  double moments[6] = {0, 0, 0, 0, 0, 0};
  double roundoff[6] = {0, 0, 0, 0, 0, 0};
};

// Half a unit of the last digit of a decimal number as written ("0.0125" -> 5e-5); 0 for
// text without a fraction or exponent ("0", "3"), which is taken as exact.
double written_roundoff(const char* text);

// The rotational inertia about the centre of mass (in the <inertial> frame) that the
// loader uses for link `link`, after the policy:
// - every policy: a non-finite number, or a negative mass, is an error;
// - a principal moment below zero: strict refuses it; repair clamps it to 0 (reported);
//   accept loads it as written with a warning, saying whether it is within the file's
//   round-off of zero (|E|_F of the six round-offs bounds how far rounding the numbers
//   moves an eigenvalue, Weyl's inequality): the dynamics stay defined as long as the body
//   the link rides on stays positive semi-definite, which validate() checks;
// - the triangle inequality violated beyond round-off (the largest moment more than the
//   sum of the other two): accept loads it as written with a warning, strict refuses it,
//   repair raises the two smaller moments by half the deficit each (reported).
// Accept never changes a number. Warnings and repairs are appended to `warnings`, one
// line per finding naming the link.
Matrix3 checked_rotational_inertia(const std::string& link, const WrittenInertia& written, InertiaPolicy policy,
                                   std::vector<std::string>& warnings);

// The floor a repair gives a body whose joint moves nothing: a point mass of 1e-3 of the
// robot's mass (1e-3 kg for a massless robot) with the rotational inertia of a solid
// sphere of 1 cm radius, at the body's origin (on its joint axis).
Matrix6 floor_inertia(double robot_mass);

// Numbers in the loader's messages: six significant digits ("%.6g"), so that a moment of
// 3.2e-09 does not read 0.000000.
std::string inertia_number(double x);

}  // namespace achd
