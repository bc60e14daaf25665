#pragma once
// Generated benchmark problems: random serial chains as URDF text (so that achd and KDL
// read the same robot) and random cases with every input nonzero.
#include <string>

#include "achd/achd.hpp"

namespace achd::bench {

// A chain link0 -> link<links> of continuous joints with arbitrary unit axes, random
// joint origins (position and rpy) and random physical inertias (com off the joint,
// principal axes rotated). Deterministic in `seed`.
std::string random_chain_urdf(int links, unsigned seed);

// q, qd, ff_torques in [-1, 1], a random wrench on every link, `nc` random constraint
// directions with random beta; gravity -9.81 z. Deterministic in `seed`.
Case random_case(const Model& model, int nc, unsigned seed);

// The robots/ directory of the source tree.
std::string robots_dir();

}  // namespace achd::bench
