#include "achd/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "achd/error.hpp"
#include "check_workspace.hpp"
#include "free_joint.hpp"
#include "joint.hpp"
#include "matrix3_pairs.hpp"
#include "sin_cos.hpp"

namespace achd {

Transform joint_transform(const Body& b, double q) {
  // Revolute: X_tree followed by a turn of q about z, R = R_tree Rz(q), whose first two
  // columns mix: [c r0 + s r1, -s r0 + c r1, r2]. Prismatic: a slide of q along z.
  Transform X = b.X_tree;
  if (is_rotational(b)) {
    double s, c;
    sin_cos(q, s, c);
    X.R.col(0) = c * b.X_tree.R.col(0) + s * b.X_tree.R.col(1);
    X.R.col(1) = c * b.X_tree.R.col(1) - s * b.X_tree.R.col(0);
  } else {
    X.p = b.X_tree.p + q * b.X_tree.R.col(2);
  }
  return X;
}

void body_poses(const Model& model, const Eigen::VectorXd& q, std::vector<Transform>& X0,
                std::vector<Vector3>& r) {
  // Joints in blocks: the sines and cosines of a block's angles first, two at a time.
  // They do not depend on the poses, so they overlap one another rather than each
  // waiting behind the chain of rotations (that wait cost 10 ns per joint here).
  constexpr int kBlock = 8;
  double sines[kBlock], cosines[kBlock];
  const int n = model.num_rates();
  Mat3p R;  // the last body's axes: the next one's parent in a chain (a tree reloads them)
  // A floating base: the free joint's six bodies from q[0..6], then body i's angle is
  // q[i + 1] (free_joint.hpp).
  int first = 0;
  const double* angle = q.data();
  if (model.floating) {
    free_joint_poses(q.data(), X0.data(), r.data());
    first = kFreeJointBodies;
    angle = q.data() + 1;
    R = load_columns(X0[first - 1].R);
  }
  for (int i0 = first; i0 < n; i0 += kBlock) {
    const int m = std::min(kBlock, n - i0);
    for (int j = 0; j < m; j += 2) {
      const double x[2] = {angle[i0 + j], j + 1 < m ? angle[i0 + j + 1] : 0.0};
      double s[2], c[2];
      sin_cos(x, s, c);
      sines[j] = s[0], cosines[j] = c[0];
      if (j + 1 < m) sines[j + 1] = s[1], cosines[j + 1] = c[1];
    }
    for (int i = i0; i < i0 + m; ++i) {
      const Body& b = model.bodies[i];
      const int p = b.parent;
      Mat3p T;  // R_parent R_tree: the joint frame at q = 0
      Vec3p ri;
      if (p < 0) {
        T = load_columns(b.X_tree.R);
        ri = load3(b.X_tree.p.data());
      } else {
        if (p != i - 1) R = load_columns(X0[p].R);  // a branch starts: its parent's axes
        T = product(R, b.X_tree.R.data());
        ri = times(R, b.X_tree.p.data());
      }
      if (is_rotational(b)) {
        const double s = sines[i - i0], c = cosines[i - i0];
        const Vec3p t0 = T.col[0];
        T.col[0] = t0 * c + T.col[1] * s;
        T.col[1] = T.col[1] * c - t0 * s;
      } else {
        ri = ri + T.col[2] * angle[i];
      }
      R = T;
      store_columns(X0[i].R, T);
      store3(r[i].data(), ri);
      X0[i].p = p < 0 ? r[i] : Vector3(X0[p].p + r[i]);
    }
  }
}

void integrate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double h,
               Eigen::VectorXd& out) {
  out.resize(q.size());
  if (!model.floating) {
    out = q + h * v;
    return;
  }
  // joints after the free joint: q[i + 1] += h v[i]
  for (int i = kFreeJointBodies; i < model.num_rates(); ++i) out[i + 1] = q[i + 1] + h * v[i];
  for (int k = 0; k < 3; ++k) out[k] = q[k] + h * v[k];
  // the orientation: exp(h w) on the left (w in world axes); for a small turn the sine
  // over the angle by its series, which stays accurate where the quotient would not
  const Vector3 turn = h * Vector3(v[3], v[4], v[5]);
  const double angle = turn.norm();
  const double c = std::cos(angle / 2);
  const double s = angle > 1e-4 ? std::sin(angle / 2) / angle : 0.5 - angle * angle / 48;
  const Eigen::Quaterniond d(c, s * turn[0], s * turn[1], s * turn[2]);
  Eigen::Quaterniond r(q[6], q[3], q[4], q[5]);
  r.coeffs() /= r.coeffs().cwiseAbs().maxCoeff();  // (a quaternion of 1e-200 normalises too)
  const Eigen::Quaterniond next = (d * r).normalized();
  out[3] = next.x(), out[4] = next.y(), out[5] = next.z(), out[6] = next.w();
}

void configuration_rate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        Eigen::VectorXd& rate) {
  rate.resize(q.size());
  if (!model.floating) {
    rate = v;
    return;
  }
  for (int i = kFreeJointBodies; i < model.num_rates(); ++i) rate[i + 1] = v[i];
  for (int k = 0; k < 3; ++k) rate[k] = v[k];
  // d(quaternion)/dt = 1/2 [w; 0] (x) h: with h = (x, y, z; s) and w = (a, b, c)
  const double a = v[3], b = v[4], c = v[5], x = q[3], y = q[4], z = q[5], s = q[6];
  rate[3] = 0.5 * (a * s + b * z - c * y);
  rate[4] = 0.5 * (b * s + c * x - a * z);
  rate[5] = 0.5 * (c * s + a * y - b * x);
  rate[6] = -0.5 * (a * x + b * y + c * z);
}

void normalise_configuration(const Model& model, Eigen::VectorXd& q) {
  if (!model.floating) return;
  Eigen::Quaterniond h(q[6], q[3], q[4], q[5]);
  h.coeffs() /= h.coeffs().cwiseAbs().maxCoeff();
  h.normalize();
  q[3] = h.x(), q[4] = h.y(), q[5] = h.z(), q[6] = h.w();
}

ChainWorkspace::ChainWorkspace(const Model& model)
    : X0(model.num_rates()),
      r(model.num_rates(), Vector3::Zero()),
      v(model.num_rates(), Vector6::Zero()),
      a(model.num_rates(), Vector6::Zero()),
      f(model.num_rates(), Vector6::Zero()),
      Xup(model.num_rates()),
      Ic(model.num_rates(), Matrix6::Zero()) {}

void check_workspace_call(const char* function, const Model& model, const ChainWorkspace& ws,
                          const Eigen::VectorXd& q) {
  const int n = model.num_rates();
  if (q.size() != model.num_positions())
    throw Error(std::string(function) + ": q must have " + std::to_string(model.num_positions()) +
                " values" + (model.floating ? " (7 of the floating base, then one per joint)" : "") +
                ", got " + std::to_string(q.size()));
  if (model.floating && !(q.segment<4>(3).lpNorm<Eigen::Infinity>() > 0 && q.segment<4>(3).allFinite()))
    throw Error(std::string(function) + ": q[3..6], the floating base's orientation quaternion, must be finite "
                "and nonzero");
  if (static_cast<int>(ws.X0.size()) != n || static_cast<int>(ws.Ic.size()) != n)
    throw Error(std::string(function) + ": the workspace was made for a model with " +
                std::to_string(ws.X0.size()) + " joints, this one has " + std::to_string(n));
}

void forward_kinematics(const Model& model, const Eigen::VectorXd& q, ChainWorkspace& ws,
                        std::vector<Transform>& poses) {
  check_workspace_call("forward_kinematics", model, ws, q);
  body_poses(model, q, ws.X0, ws.r);
  poses.resize(model.num_links());
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    poses[l] = link.body < 0 ? link.offset : ws.X0[link.body] * link.offset;
  }
}

std::vector<Transform> forward_kinematics(const Model& model, const Eigen::VectorXd& q) {
  ChainWorkspace ws(model);
  std::vector<Transform> poses(model.num_links());
  forward_kinematics(model, q, ws, poses);
  return poses;
}

void link_velocities(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     ChainWorkspace& ws, std::vector<Vector6>& velocities) {
  check_workspace_call("link_velocities", model, ws, q);
  if (qd.size() != model.num_rates())
    throw Error("link_velocities: qd must have " + std::to_string(model.num_rates()) + " values, got " +
                std::to_string(qd.size()));
  body_poses(model, q, ws.X0, ws.r);
  double free_rates[kFreeJointBodies];  // a floating base's rates in the solver's form
  if (model.floating) free_joint_rates(ws.X0[kFreeJointBodies - 1].R, qd.data(), free_rates);
  // Body velocity in base orientation, at the body origin: v_i = v_p (moved by r_i) + S qd.
  std::vector<Vector6>& vb = ws.v;
  for (int i = 0; i < model.num_rates(); ++i) {
    const Body& b = model.bodies[i];
    Vector6 vi = Vector6::Zero();
    if (b.parent >= 0) vi = motion_shift(vb[b.parent], ws.r[i]);
    const Vector6 sj = subspace_times(b, model.floating && i < kFreeJointBodies ? free_rates[i] : qd[i]);
    vi.head<3>() += ws.X0[i].R * sj.head<3>();
    vi.tail<3>() += ws.X0[i].R * sj.tail<3>();
    vb[i] = vi;
  }
  velocities.resize(model.num_links());
  for (int l = 0; l < model.num_links(); ++l) {
    const Link& link = model.links[l];
    velocities[l] = link.body < 0 ? Vector6::Zero().eval()
                                  : motion_shift(vb[link.body], ws.X0[link.body].R * link.offset.p);
  }
}

std::vector<Vector6> link_velocities(const Model& model, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& qd) {
  ChainWorkspace ws(model);
  std::vector<Vector6> velocities(model.num_links());
  link_velocities(model, q, qd, ws, velocities);
  return velocities;
}

namespace {

// Joint i's axis in base axes for the Jacobians: the body's z axis, except for the free
// joint's rotations, whose rates are world angular velocities (free_joint.hpp).
Vector3 jacobian_axis(const Model& model, const ChainWorkspace& ws, int i) {
  if (model.floating && i >= 3 && i < kFreeJointBodies) return Vector3::Unit(i - 3);
  return ws.X0[i].R.col(2);
}

}  // namespace

void link_jacobian(const Model& model, const Eigen::VectorXd& q, int link, const Vector3& point,
                   ChainWorkspace& ws, Eigen::MatrixXd& J) {
  check_workspace_call("link_jacobian", model, ws, q);
  if (link < 0 || link >= model.num_links())
    throw Error("link_jacobian: link index " + std::to_string(link) + " is not in the model (" +
                std::to_string(model.num_links()) + " links after the root)");
  body_poses(model, q, ws.X0, ws.r);
  const Link& l = model.links[link];
  J.setZero(6, model.num_rates());
  if (l.body < 0) return;  // fixed to the root: no joint moves it
  const Transform& X = ws.X0[l.body];
  const Vector3 p = X.p + X.R * (l.offset.p + l.offset.R * point);  // the point, base frame
  // Column i, for the bodies from the link's up to the root: joint i's unit motion seen
  // at the point. Revolute: [z x (p - p_i); z]; prismatic: [z; 0], with z the joint axis
  // (the body's z) in base orientation.
  for (int i = l.body; i >= 0; i = model.bodies[i].parent) {
    const Vector3 z = jacobian_axis(model, ws, i);
    if (is_rotational(model.bodies[i])) {
      J.col(i).head<3>() = z.cross(p - ws.X0[i].p);
      J.col(i).tail<3>() = z;
    } else {
      J.col(i).head<3>() = z;
    }
  }
}

Eigen::MatrixXd link_jacobian(const Model& model, const Eigen::VectorXd& q, int link,
                              const Vector3& point) {
  ChainWorkspace ws(model);
  Eigen::MatrixXd J(6, model.num_rates());
  link_jacobian(model, q, link, point, ws, J);
  return J;
}

void tip_jacobian(const Model& model, const Eigen::VectorXd& q, ChainWorkspace& ws,
                  Eigen::MatrixXd& J) {
  check_workspace_call("tip_jacobian", model, ws, q);
  if (!model.has_tip()) throw Error("tip_jacobian: the model is a tree (loaded without a tip); use link_jacobian");
  body_poses(model, q, ws.X0, ws.r);
  const Link& tip = model.tip();
  const Vector3 p_tip = tip.body < 0 ? tip.offset.p : (ws.X0[tip.body] * tip.offset).p;
  J.setZero(6, model.num_rates());
  // Column i: joint i's unit motion seen at the tip. Revolute: [z x (p_tip - p_i); z];
  // prismatic: [z; 0], with z the joint axis (the body's z) in base orientation.
  for (int i = tip.body; i >= 0; i = model.bodies[i].parent) {
    const Body& b = model.bodies[i];
    const Vector3 z = jacobian_axis(model, ws, i);
    if (is_rotational(b)) {
      J.col(i).head<3>() = z.cross(p_tip - ws.X0[i].p);
      J.col(i).tail<3>() = z;
    } else {
      J.col(i).head<3>() = z;
    }
  }
}

Eigen::MatrixXd tip_jacobian(const Model& model, const Eigen::VectorXd& q) {
  ChainWorkspace ws(model);
  Eigen::MatrixXd J(6, model.num_rates());
  tip_jacobian(model, q, ws, J);
  return J;
}

}  // namespace achd
