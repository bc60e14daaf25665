#include "four_bar_reference.hpp"

#include <cmath>

namespace achd::test::four_bar {
namespace {

// A planar vector (x, z).
struct P2 {
  double x = 0, z = 0;
};
P2 operator+(P2 u, P2 v) { return {u.x + v.x, u.z + v.z}; }
P2 operator*(double s, P2 u) { return {s * u.x, s * u.z}; }
double dot(P2 u, P2 v) { return u.x * v.x + u.z * v.z; }

// e(phi) = (cos phi, -sin phi): the direction of a link at absolute angle phi about +y.
P2 e(double phi) { return {std::cos(phi), -std::sin(phi)}; }
// n(phi) = de/dphi = (-sin phi, -cos phi); dn/dphi = -e.
P2 n(double phi) { return {-std::sin(phi), -std::cos(phi)}; }

constexpr double kPi = 3.14159265358979323846;

}  // namespace

Parameters parameters() {
  // robots/four_bar.urdf: these numbers must match the file. Steel bars 20 mm wide (in the
  // plane) and 5 mm thick, 0.785 kg/m: m = 0.785 L, com at L / 2, Iyy = m (L^2 + 0.02^2) / 12.
  Parameters p;
  p.ground = 0.1;
  p.crank = 0.04;
  p.coupler = 0.12;
  p.rocker = 0.08;
  p.crank_mass = 0.0314;
  p.coupler_mass = 0.0942;
  p.rocker_mass = 0.0628;
  p.crank_com = 0.02;
  p.coupler_com = 0.06;
  p.rocker_com = 0.04;
  p.crank_inertia = 5.23333e-06;
  p.coupler_inertia = 1.1618e-04;
  p.rocker_inertia = 3.55867e-05;
  p.gravity = 9.81;
  return p;
}

Closure closure(double theta, const Parameters& p) {
  const double a = p.crank, b = p.coupler, c = p.rocker, d = p.ground;
  // Triangle A O4 B in standard angles (x right, z up; standard angle = -phi). A is the
  // crank pin, r = O4 - A, rho = |r|, gamma its angle. B left of A -> O4:
  //   theta3 = gamma + beta,        cos beta  = (b^2 + rho^2 - c^2) / (2 b rho)   (at A)
  //   theta4 = gamma + pi - delta,  cos delta = (c^2 + rho^2 - b^2) / (2 c rho)   (at O4)
  // r_x >= d - a > 0 keeps gamma in (-pi/2, pi/2), so both are continuous in theta.
  const P2 A = a * e(theta);
  const P2 r{d - A.x, -A.z};
  const double rho = std::sqrt(dot(r, r));
  const double gamma = std::atan2(r.z, r.x);
  const double beta = std::acos((b * b + rho * rho - c * c) / (2 * b * rho));
  const double delta = std::acos((c * c + rho * rho - b * b) / (2 * c * rho));
  const double phi2 = theta;
  const double phi3 = -(gamma + beta);
  const double phi4 = -(gamma + kPi - delta);

  // Differentiating the loop equation (1) of the header:
  //   a n2 + b n3 phi3' - c n4 phi4' = 0. Dotted with e4 and e3
  // (n_i . e_j = sin(phi_j - phi_i), e_i . e_j = cos(phi_i - phi_j)):
  //   phi3' = -a sin(phi4 - phi2) / (b sin(phi4 - phi3))
  //   phi4' =  a sin(phi3 - phi2) / (c sin(phi3 - phi4))
  const double s43 = std::sin(phi4 - phi3);
  const double c34 = std::cos(phi3 - phi4);
  const double d3 = -a * std::sin(phi4 - phi2) / (b * s43);
  const double d4 = a * std::sin(phi3 - phi2) / (c * -s43);
  // Again: -a e2 - b e3 phi3'^2 + b n3 phi3'' + c e4 phi4'^2 - c n4 phi4'' = 0, so
  //   phi3'' = (a cos(phi2 - phi4) + b cos(phi3 - phi4) phi3'^2 - c phi4'^2)
  //            / (b sin(phi4 - phi3))
  //   phi4'' = (-a cos(phi2 - phi3) - b phi3'^2 + c cos(phi3 - phi4) phi4'^2)
  //            / (c sin(phi3 - phi4))
  const double dd3 = (a * std::cos(phi2 - phi4) + b * c34 * d3 * d3 - c * d4 * d4) / (b * s43);
  const double dd4 = (-a * std::cos(phi2 - phi3) - b * d3 * d3 + c * c34 * d4 * d4) / (c * -s43);

  // Joint coordinates: q1 = phi3 - phi2, q2 = phi4.
  Closure k;
  k.q[0] = theta;
  k.q[1] = phi3 - phi2;
  k.q[2] = phi4;
  k.dq[0] = 1;
  k.dq[1] = d3 - 1;
  k.dq[2] = d4;
  k.ddq[0] = 0;
  k.ddq[1] = dd3;
  k.ddq[2] = dd4;
  return k;
}

Terms terms(double theta, const Parameters& p) {
  const Closure k = closure(theta, p);
  const double phi2 = theta, phi3 = theta + k.q[1], phi4 = k.q[2];
  const double d3 = 1 + k.dq[1], d4 = k.dq[2], dd3 = k.ddq[1], dd4 = k.ddq[2];
  const P2 e2 = e(phi2), e3 = e(phi3), e4 = e(phi4), n2 = n(phi2), n3 = n(phi3), n4 = n(phi4);

  // Centres of mass c2 = r2 e2, c3 = a e2 + r3 e3, c4 = (d, 0) + r4 e4, and their first
  // and second derivatives in theta (de/dtheta = n phi', dn/dtheta = -e phi').
  const double r2 = p.crank_com, r3 = p.coupler_com, r4 = p.rocker_com, a = p.crank;
  const P2 c2 = r2 * e2, c3 = a * e2 + r3 * e3, c4 = P2{p.ground, 0} + r4 * e4;
  const P2 dc2 = r2 * n2;
  const P2 dc3 = a * n2 + (r3 * d3) * n3;
  const P2 dc4 = (r4 * d4) * n4;
  const P2 ddc2 = -r2 * e2;
  const P2 ddc3 = -a * e2 + r3 * (dd3 * n3 + (-d3 * d3) * e3);
  const P2 ddc4 = r4 * (dd4 * n4 + (-d4 * d4) * e4);

  const double m2 = p.crank_mass, m3 = p.coupler_mass, m4 = p.rocker_mass;
  const double I2 = p.crank_inertia, I3 = p.coupler_inertia, I4 = p.rocker_inertia;
  Terms t;
  // m = sum m_i |c_i'|^2 + I_i phi_i'^2 (phi2' = 1),
  // m' = sum 2 m_i c_i' . c_i'' + 2 I_i phi_i' phi_i''.
  t.m = m2 * dot(dc2, dc2) + m3 * dot(dc3, dc3) + m4 * dot(dc4, dc4) + I2 + I3 * d3 * d3 +
        I4 * d4 * d4;
  t.dm = 2 * (m2 * dot(dc2, ddc2) + m3 * dot(dc3, ddc3) + m4 * dot(dc4, ddc4) + I3 * d3 * dd3 +
              I4 * d4 * dd4);
  // V = g sum m_i z_i;  V' = g sum m_i dz_i/dtheta.
  t.V = p.gravity * (m2 * c2.z + m3 * c3.z + m4 * c4.z);
  t.dV = p.gravity * (m2 * dc2.z + m3 * dc3.z + m4 * dc4.z);
  return t;
}

double crank_acceleration(double theta, double thetadot, const Parameters& p) {
  const Terms t = terms(theta, p);
  return -(0.5 * t.dm * thetadot * thetadot + t.dV) / t.m;
}

double energy(double theta, double thetadot, const Parameters& p) {
  const Terms t = terms(theta, p);
  return 0.5 * t.m * thetadot * thetadot + t.V;
}

CrankState crank_motion(double theta0, double thetadot0, double t_end, double step,
                        const Parameters& p) {
  // Classical RK4 on y = (theta, thetadot), y' = (thetadot, thetaddot(theta, thetadot)).
  const long steps = static_cast<long>(std::ceil(t_end / step));
  const double h = steps > 0 ? t_end / static_cast<double>(steps) : 0.0;
  double x = theta0, v = thetadot0;
  for (long i = 0; i < steps; ++i) {
    const double k1x = v, k1v = crank_acceleration(x, v, p);
    const double k2x = v + 0.5 * h * k1v, k2v = crank_acceleration(x + 0.5 * h * k1x, k2x, p);
    const double k3x = v + 0.5 * h * k2v, k3v = crank_acceleration(x + 0.5 * h * k2x, k3x, p);
    const double k4x = v + h * k3v, k4v = crank_acceleration(x + h * k3x, k4x, p);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return {x, v};
}

}  // namespace achd::test::four_bar
