#pragma once
// What the JS wrapper mirrors from C++, declared once here: the buffers behind the
// zero-copy views, by index (the enums) and by name (the name tables, in the same order),
// and the JSON descriptions of option structs. achd_constants() (constants_api.cpp) hands
// all of it, with the effect bits, enum names and defaults, to the JS wrapper at module start;
// wasm/js holds no copy of any of them.
#include <string>

#include "achd/simulator.hpp"

namespace achd::wasm {

// achd_solver_buffer(solver, index): the solver's Case inputs, then its Data outputs.
enum SolverBuffer {
  kSolverQ, kSolverQd, kSolverFfTorques, kSolverGravity, kSolverAlpha, kSolverBeta, kSolverFExt,
  kSolverQdd, kSolverNu, kSolverJointTorques, kSolverConstraintTorques, kSolverTotalTorques,
  kSolverLinkAccelerations, kSolverConstraintWrench, kSolverDropped, kSolverConstraintWrenches,
  kSolverQddGiven, kSolverWFext, kSolverWFf, kSolverFVirtual, kSolverPrescribedTorques, kSolverVirtualTorques,
  kSolverCouplingForces, kNumSolverBuffers
};
inline constexpr const char* kSolverBufferNames[] = {
    "q", "qd", "ff_torques", "gravity", "alpha", "beta", "f_ext",
    "qdd", "nu", "joint_torques", "constraint_torques", "total_torques",
    "link_accelerations", "constraint_wrench", "dropped", "constraint_wrenches",
    "qdd_given", "w_fext", "w_ff", "f_virtual", "prescribed_torques", "virtual_torques",
    "coupling_forces"};
static_assert(sizeof kSolverBufferNames / sizeof kSolverBufferNames[0] == kNumSolverBuffers,
              "one name per SolverBuffer");

// achd_sim_buffer(sim, index): the simulator's state.
enum SimulatorBuffer { kSimQ, kSimQd, kSimT, kSimFfTorques, kSimFExt, kNumSimulatorBuffers };
inline constexpr const char* kSimulatorBufferNames[] = {"q", "qd", "t", "ff_torques", "f_ext"};
static_assert(sizeof kSimulatorBufferNames / sizeof kSimulatorBufferNames[0] == kNumSimulatorBuffers,
              "one name per SimulatorBuffer");

// achd_sim_result(sim, index): outputs of the solve at the start of the last step.
enum SimulatorResult { kSimNu, kSimJointTorques, kSimQdd, kSimPrescribedTorques, kNumSimulatorResults };
inline constexpr const char* kSimulatorResultNames[] = {"nu", "joint_torques", "qdd", "prescribed_torques"};
static_assert(sizeof kSimulatorResultNames / sizeof kSimulatorResultNames[0] == kNumSimulatorResults,
              "one name per SimulatorResult");

// achd_robot_read_input(robot, text, field, kind, out): the case-shaped inputs of the JS
// API's other calls, each read as the case parser reads that field.
enum InputKind { kInputJointPositions, kInputJointRates, kInputLinkWrenches, kInputVector3, kNumInputKinds };
inline constexpr const char* kInputKindNames[] = {"joint_positions", "joint_rates", "link_wrenches", "vector3"};
static_assert(sizeof kInputKindNames / sizeof kInputKindNames[0] == kNumInputKinds, "one name per InputKind");

// JSON objects with the option structs' fields under their snake_case names and enum
// values as their names (achd/names.hpp); effects as the bit mask.
std::string describe(const Options& o);
std::string describe(const SimulatorOptions& o);

}  // namespace achd::wasm
