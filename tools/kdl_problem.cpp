#include "kdl_problem.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "console_capture.hpp"

namespace achd::cli {
namespace {

class QuietStderr {
 public:
  QuietStderr() : saved_(dup(2)) {
    std::fflush(stderr);
    std::cerr.flush();
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 2);
      close(null);
    }
  }
  ~QuietStderr() {
    std::fflush(stderr);
    std::cerr.flush();
    if (saved_ >= 0) {
      dup2(saved_, 2);
      close(saved_);
    }
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  int saved_;
};

// kdl_parser warns through ROS's rosconsole (in colour, on stderr) and urdfdom logs
// through console_bridge; the command line's stderr is one `achd: error:` line or
// nothing. While kdl_parser runs, console_bridge's messages are captured (its first error
// goes into the message) and file descriptor 2 points at /dev/null.
bool parse_quietly(const std::string& urdf, bool is_xml, KDL::Tree& tree, std::string& why) {
  const ConsoleCapture console;
  const QuietStderr quiet;
  const bool parsed = is_xml ? kdl_parser::treeFromString(urdf, tree) : kdl_parser::treeFromFile(urdf, tree);
  why = console.first_error();
  return parsed;
}

}  // namespace

struct KdlProblem::Impl {
  KDL::Chain chain;
  std::unique_ptr<KDL::ChainHdSolver_Vereshchagin> solver;
  KDL::JntArray q, qd, qdd, ff, ct, beta;
  KDL::Jacobian alpha;
  KDL::Wrenches f_ext;
};

KdlProblem::KdlProblem(const std::string& urdf, bool is_xml, const std::string& root,
                       const std::string& tip, const Case& c)
    : impl_(std::make_unique<Impl>()) {
  Impl& k = *impl_;
  KDL::Tree tree;
  std::string why;
  if (!parse_quietly(urdf, is_xml, tree, why))
    throw Error("kdl_parser cannot read the URDF" + (why.empty() ? std::string() : ": " + why));
  if (!tree.getChain(root, tip, k.chain)) throw Error("KDL: no chain " + root + " -> " + tip);
  // KDL's solver indexes its joint arrays by segment: a fixed joint (a segment without a
  // joint) makes it read past them (an Eigen assertion, or garbage without assertions).
  for (const KDL::Segment& segment : k.chain.segments)
    if (segment.getJoint().getType() == KDL::Joint::None)
      throw Error("KDL's ChainHdSolver_Vereshchagin cannot solve a chain with fixed joints (it needs "
                  "one movable joint per segment), and the chain " + root + " -> " + tip +
                  " has the fixed joint '" + segment.getJoint().getName() +
                  "'; compare with KDL on a chain without fixed joints");
  const unsigned nj = k.chain.getNrOfJoints();
  const int nc = c.num_constraints();
  if (static_cast<int>(nj) != c.q.size()) throw Error("KDL: joint count differs from achd's");
  // KDL's root acceleration is the fictitious base acceleration -g.
  const KDL::Twist root_acc(KDL::Vector(-c.gravity.x(), -c.gravity.y(), -c.gravity.z()),
                            KDL::Vector::Zero());
  k.solver = std::make_unique<KDL::ChainHdSolver_Vereshchagin>(k.chain, root_acc, nc);
  k.q = k.qd = k.qdd = k.ff = k.ct = KDL::JntArray(nj);
  for (unsigned i = 0; i < nj; ++i) {
    k.q(i) = c.q[i];
    if (c.qd.size()) k.qd(i) = c.qd[i];
    if (c.ff_torques.size()) k.ff(i) = c.ff_torques[i];
  }
  k.alpha = KDL::Jacobian(nc);
  k.beta = KDL::JntArray(nc);
  for (int j = 0; j < nc; ++j) {
    for (int r = 0; r < 6; ++r) k.alpha(r, j) = c.alpha(r, j);
    k.beta(j) = c.beta[j] - c.alpha.col(j).head<3>().dot(c.gravity);  // beta_kdl
  }
  k.f_ext.assign(k.chain.getNrOfSegments(), KDL::Wrench::Zero());
  for (std::size_t l = 0; l < c.f_ext.size() && l < k.f_ext.size(); ++l) {
    const Vector6& w = c.f_ext[l];
    k.f_ext[l] = KDL::Wrench(KDL::Vector(w[0], w[1], w[2]), KDL::Vector(w[3], w[4], w[5]));
  }
}

KdlProblem::~KdlProblem() = default;

void KdlProblem::solve() {
  Impl& k = *impl_;
  const int err = k.solver->CartToJnt(k.q, k.qd, k.qdd, k.alpha, k.beta, k.f_ext, k.ff, k.ct);
  if (err < 0) throw Error("KDL's CartToJnt failed with code " + std::to_string(err));
}

Eigen::VectorXd KdlProblem::qdd() const { return impl_->qdd.data; }

}  // namespace achd::cli
