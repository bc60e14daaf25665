#include "achd/spatial.hpp"

#include <string>

#include "achd/error.hpp"
#include "spatial_pairs.hpp"

namespace achd {

Matrix6 spatial_inertia(double mass, const Vector3& com, const Matrix3& inertia_at_com) {
  const Matrix3 cx = skew(com);
  Matrix6 I;
  I.topLeftCorner<3, 3>() = mass * Matrix3::Identity();
  I.topRightCorner<3, 3>() = -mass * cx;
  I.bottomLeftCorner<3, 3>() = mass * cx;
  I.bottomRightCorner<3, 3>() = inertia_at_com - mass * cx * cx;
  return I;
}

namespace {

// Not inlined: with add_shifted inlined into add_inertia_to_parent, Emscripten 3.1.6's
// clang (-O2 and up, -msimd128) computed the wrong shift (a compiler bug, reproduced in
// isolation; called through this function it is right). Only the loader and CRBA come
// through here.
__attribute__((noinline)) void add_shifted_out_of_line(const Matrix6& I, const Vector3& p, Matrix6& Ip) {
  add_shifted(I, Shift(p), Ip);
}

}  // namespace

void add_inertia_to_parent(const Transform& X, const Matrix6& Ic, Matrix6& Ip) {
  // Rotate the blocks [A B; B^T C] into P's orientation: A' = R A R^T, B' = R B R^T, C';
  // then shift the reference point from C's origin to P's origin.
  const Matrix3& R = X.R;
  const Mat3p Rc = load_columns(R);
  Matrix3 A, C;
  store_columns(A, rotate_symmetric(Rc, Ic.data(), 6));
  store_columns(C, rotate_symmetric(Rc, Ic.data() + 6 * 3 + 3, 6));
  Matrix6 I;
  I.topLeftCorner<3, 3>() = A;
  I.topRightCorner<3, 3>() = R * Ic.topRightCorner<3, 3>() * R.transpose();
  I.bottomLeftCorner<3, 3>() = I.topRightCorner<3, 3>().transpose();
  I.bottomRightCorner<3, 3>() = C;
  add_shifted_out_of_line(I, X.p, Ip);
}

Matrix6 inertia_to_parent(const Transform& X, const Matrix6& Ic) {
  Matrix6 I = Matrix6::Zero();
  add_inertia_to_parent(X, Ic, I);
  return I;
}

namespace {
const char* const kDirectionNames[kNumDirections] = {"x", "y", "z", "rx", "ry", "rz"};
}  // namespace

const char* direction_name(int index) {
  if (index < 0 || index >= kNumDirections)
    throw Error("direction index " + std::to_string(index) + " is not in 0..5 (x y z rx ry rz)");
  return kDirectionNames[index];
}

int index_of_direction(const std::string& name) {
  for (int k = 0; k < kNumDirections; ++k)
    if (name == kDirectionNames[k]) return k;
  return -1;
}

}  // namespace achd
