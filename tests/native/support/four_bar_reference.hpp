#pragma once
// An independent reference for the one-degree-of-freedom motion of robots/four_bar.urdf
// closed by robots/four_bar.loops.json (the planar crank-rocker four-bar): closed-form
// loop closure and a Lagrange equation in the crank angle, integrated by RK4. It uses
// only the standard library, not achd.
//
// Coordinates. The mechanism moves in the x-z plane; every joint turns about +y, so a
// positive angle turns +x towards -z. A link at absolute angle phi points along
// e(phi) = (cos phi, -sin phi) in (x, z); n(phi) = de/dphi = (-sin phi, -cos phi).
// With the crank joint angle theta = q[0] (crank_joint), the absolute link angles are
//   phi2 = theta (crank), phi3 = theta + q[1] (coupler), phi4 = q[2] (rocker),
// and the loop closes when the coupler's far end meets the rocker's far end:
//   a e(phi2) + b e(phi3) = (d, 0) + c e(phi4)                                  (1)
// (a, b, c, d: crank, coupler, rocker, ground lengths).
//
// Assembly branch: the coupler-rocker pin B lies to the left of the line from the crank
// pin A to the rocker pivot O4 as seen with x to the right and z up (B above the ground
// line when the crank is horizontal). In a Grashof crank-rocker |b - c| < |A - O4| <
// b + c for every theta, so this branch is smooth in theta for all theta.
//
// Start pose: theta0 = start_theta = -pi/2 (crank straight up), closed at
//   q0 = [-1.5707963267948966, 1.2411402364746327, -1.4007473763557965]
// (robots/README.md). From rest there the linkage swings under gravity: the crank turns
// through about 345 degrees and back in the first second, theta(1 s) = -1.2470310356084366
// rad. The crank of a crank-rocker turns fully, so the crank angle has no dead point and
// the equation of motion below is regular for every theta.
namespace achd::test::four_bar {

// Parameters of the linkage. Link lengths are pivot-to-pivot along each link's x axis,
// centres of mass on that axis, inertias about y at the centre of mass.
struct Parameters {
  double ground = 0;   // d: crank pivot O2 (root origin) to rocker pivot O4, along +x
  double crank = 0;    // a
  double coupler = 0;  // b
  double rocker = 0;   // c
  double crank_mass = 0, coupler_mass = 0, rocker_mass = 0;
  double crank_com = 0, coupler_com = 0, rocker_com = 0;                // from each link's origin
  double crank_inertia = 0, coupler_inertia = 0, rocker_inertia = 0;  // Iyy at the com
  double gravity = 0;  // g: gravity is (0, 0, -g)
};

// The parameters of robots/four_bar.urdf (the same numbers; they must match the file).
Parameters parameters();

// The crank angle of the documented start pose: the crank points straight up.
inline constexpr double start_theta = -1.5707963267948966;

// The closed pose at crank angle theta on the documented branch: the joint angles
// q = [theta, coupler_joint, rocker_joint] and their first and second derivatives
// with respect to theta (so qd = dq * thetadot, qdd = dq * thetaddot + ddq * thetadot^2).
struct Closure {
  double q[3] = {0, 0, 0};
  double dq[3] = {1, 0, 0};
  double ddq[3] = {0, 0, 0};
};
Closure closure(double theta, const Parameters& p = parameters());

// The terms of the Lagrange equation in theta:
//   T = 1/2 m(theta) thetadot^2,  m = sum_i m_i |dc_i/dtheta|^2 + I_i (dphi_i/dtheta)^2,
//   V = sum_i m_i g z_i (c_i the centre of mass of link i, z_i its height),
//   m(theta) thetaddot + 1/2 m'(theta) thetadot^2 + V'(theta) = 0,
// with m' and V' from the analytic second derivatives of the closure.
struct Terms {
  double m = 0, dm = 0;  // m(theta), m'(theta)
  double V = 0, dV = 0;  // V(theta), V'(theta)
};
Terms terms(double theta, const Parameters& p = parameters());

// thetaddot = -(1/2 m' thetadot^2 + V') / m.
double crank_acceleration(double theta, double thetadot, const Parameters& p = parameters());

// T + V.
double energy(double theta, double thetadot, const Parameters& p = parameters());

// The crank's state after integrating the equation of motion from (theta0, thetadot0)
// at t = 0 to t_end with classical RK4 at a fixed step of at most `step` seconds (the
// step is t_end / ceil(t_end / step)).
struct CrankState {
  double theta = 0, thetadot = 0;
};
CrankState crank_motion(double theta0, double thetadot0, double t_end, double step = 1e-5,
                        const Parameters& p = parameters());

}  // namespace achd::test::four_bar
