// The README's C++ quick start, built against the installed package: holds the LWR's
// tip still along base z and checks the constraint it asked for (alpha^T a_tip = beta).
#include <achd/achd.hpp>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  achd::Model model = achd::load_urdf_file(argv[1], "lwr_base_link", "lwr_link_7");
  achd::Data data(model);
  achd::Case c = achd::Case::zeros(model);
  c.q << 0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1;
  c.alpha.resize(6, 1);
  c.alpha.col(0) << 0, 0, 1, 0, 0, 0;
  c.beta.setZero(1);
  achd::hybrid_dynamics(model, data, c);
  const double tip_z = data.link_accelerations.back()[2];
  std::printf("tip z acceleration %.3g, nu %.6g, rank %d\n", tip_z, data.nu[0], data.rank);
  return std::abs(tip_z) < 1e-9 && data.rank == 1 ? 0 : 1;
}
