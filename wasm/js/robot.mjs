// A loaded robot (achd.loadURDF): its description, solves and algorithms.
import { ACHD_OLD_INTEGRATOR_NAMES, achdConstants, achdDeprecated } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { ACHD_SOLVER_OPTION_KEYS, achdCheckObject, achdChoice, achdDescribe, achdEffectBits, achdOptionalObject, achdPositive, achdReadNumbers, achdSolverOptions } from './validation.mjs';
import { achdColumns, achdDriverWeights, achdJointValues, achdLinkWrenches, achdPackBlocks, achdPrescribedJoints } from './case_names.mjs';
import { achdChunks, achdWithScratch, achdWithString } from './memory.mjs';
import { AchdHandle } from './handle.mjs';
import { Solver } from './solver.mjs';
import { Simulator } from './simulator.mjs';

export class Robot extends AchdHandle {
  constructor(ptr) {
    super('Robot', ptr, achdWasm.module._achd_robot_delete);
    const info = JSON.parse(achdWasm.text.UTF8ToString(achdWasm.module._achd_robot_info(ptr)));
    const bound = (x) => (Math.abs(x) >= 1e300 ? Math.sign(x) * Infinity : x);
    this.root = info.root;
    this.tip = info.tip;  // null for a tree
    // Joints the loader held fixed (options.locked, a chain's side joints), [{name, value}].
    this.lockedJoints = info.locked_joints;
    // What the loader found odd in the URDF but loaded, or repaired (options.inertia), one
    // line per finding naming the link.
    this.warnings = info.warnings;
    // Coupled joints (URDF <mimic>, loaded coupled by default): [{joint, leader,
    // multiplier, offset}], q_joint = multiplier q_leader + offset in every solve.
    this.couplings = info.couplings;
    // With a floating base (options.floating) the free joint comes first in jointNames, named
    // after the root link, with 7 of the numPositions numbers of q and 6 of the numJoints
    // numbers of qd, qdd and the torques; without one both counts are the joints'.
    this.floating = info.floating;
    this.numJoints = info.num_joints;
    this.numPositions = info.num_positions;
    this.numLinks = info.links.length;
    this.jointNames = info.joints.map((j) => j.name);
    this.jointTypes = info.joints.map((j) => j.type);
    this.limits = info.joints.map((j) => ({
      lower: bound(j.lower), upper: bound(j.upper), velocity: j.velocity, effort: j.effort,
    }));
    this.damping = info.joints.map((j) => j.damping);
    this.friction = info.joints.map((j) => j.friction);
    this.linkNames = info.links;
    this._solver = null;  // the solver behind solve(), created on first use
  }
  // robot.defaultPose: q with every joint at 0, or the middle of its limits when 0 is
  // outside them (a floating base at the identity); robot.poses: {name: q} of the SRDF's
  // group_states (loadURDF's options.srdf); robot.startPose: the one options.pose names,
  // else defaultPose. q in model order (numPositions numbers).
  _readPoses(srdf, pose) {
    const text = srdf === '' ? '<robot/>' : srdf;
    const json = achdWithString(text, (p) => achdWasm.module._achd_robot_poses(this._live(), p));
    if (!json) throw achdLastError();
    const info = JSON.parse(achdWasm.text.UTF8ToString(json));
    this.defaultPose = info.default;
    this.poses = Object.create(null);
    for (const p of info.poses) this.poses[p.name] = p.q;
    if (pose !== undefined && !Object.prototype.hasOwnProperty.call(this.poses, pose))
      throw new Error(`loadURDF: options.pose: the SRDF has no group_state '${pose}' (it has ${Object.keys(this.poses).map((n) => `'${n}'`).join(', ') || 'none'})`);
    this.startPose = pose === undefined ? this.defaultPose : this.poses[pose];
  }
  delete() {
    if (this._solver) this._solver.delete();
    this._solver = null;
    super.delete();
  }
  createSolver(options) {
    if (options === undefined) options = {};  // (null: a named error)
    const o = achdCheckObject(options, 'options', ACHD_SOLVER_OPTION_KEYS);
    const max = achdConstants().max_constraints;
    const mc = o.maxConstraints === undefined ? max : o.maxConstraints;
    // (checked here: C++ takes an int, which would print 2**31 as -2147483648)
    if (!Number.isInteger(mc) || mc < 0 || mc > max)
      throw new Error(`options.maxConstraints must be an integer in [0, ${max}], got ${achdDescribe(mc)}`);
    const args = achdSolverOptions(o);
    const s = achdWasm.module._achd_solver_create(this._live(), mc);
    if (!s) throw achdLastError();
    achdWasm.module._achd_solver_set_options(s, ...args);
    return new Solver(this, s, mc);  // gravity: the C++ Case's default
  }
  // The case object in, the result object out (docs/design.md section 5; plain arrays:
  // copies). q, qd, ff_torques by joint name and f_ext, f_virtual by link name as in the
  // CLI; qdd_given by joint name or in model order (null: the torque is given); w_fext,
  // w_ff per tip column; constraints: blocks {link (a name), alpha, beta, point, w_fext, w_ff}.
  // Every input is read (once) and checked before anything is written to the solver.
  solve(c, options) {
    this._live();
    c = achdCheckObject(c, 'the case', ['q', 'qd', 'gravity', 'alpha', 'beta', 'f_ext', 'ff_torques', 'constraints',
      'qdd_given', 'w_fext', 'w_ff', 'f_virtual']);
    if (!('q' in c)) throw new Error("missing required field 'q'");
    if (!('gravity' in c)) throw new Error("missing required field 'gravity'");
    const args = achdSolverOptions(options);
    const nj = this.numJoints, max = achdConstants().max_constraints;
    const q = achdJointValues(c.q, 'q', this, true);
    const gravity = achdReadNumbers(c.gravity, 'gravity', 3);
    const qd = c.qd === undefined ? new Float64Array(nj) : achdJointValues(c.qd, 'qd', this);
    const ff = c.ff_torques === undefined ? new Float64Array(nj) : achdJointValues(c.ff_torques, 'ff_torques', this);
    const tip = c.alpha === undefined ? achdColumns([], c.beta, '', max) : achdColumns(c.alpha, c.beta, '', max);
    const nc = tip.count;
    const w_fext = achdDriverWeights(c.w_fext, 'w_fext', nc), w_ff = achdDriverWeights(c.w_ff, 'w_ff', nc);
    const blocks = achdPackBlocks(c.constraints === undefined ? [] : c.constraints, this, max);
    const f_ext = c.f_ext === undefined ? null : achdLinkWrenches(c.f_ext, this, 'f_ext');
    const f_virtual = c.f_virtual === undefined ? null : achdLinkWrenches(c.f_virtual, this, 'f_virtual');
    const given = c.qdd_given === undefined ? null : achdPrescribedJoints(c.qdd_given, this);
    // Read and checked: now the robot must still be there (a Proxy's trap may have deleted it).
    this._live();
    if (!this._solver) this._solver = this.createSolver();
    const s = this._solver, ptr = s._ptr, names = s._bufferNames(), heap = achdWasm.module.HEAPF64;
    const at = (name) => achdWasm.module._achd_solver_buffer(ptr, names.indexOf(name)) >> 3;
    heap.set(q, at('q'));
    heap.set(gravity, at('gravity'));
    heap.set(qd, at('qd'));
    heap.set(ff, at('ff_torques'));
    heap.set(tip.alpha, at('alpha'));
    heap.set(tip.beta, at('beta'));
    heap.set(w_fext, at('w_fext'));
    heap.set(w_ff, at('w_ff'));
    s._setBlocks(blocks);  // (its scratch may grow the memory: HEAPF64 is read again below)
    if (f_ext) achdWasm.module.HEAPF64.set(f_ext, at('f_ext'));
    s.useExternalWrenches = f_ext !== null;
    if (f_virtual) achdWasm.module.HEAPF64.set(f_virtual, at('f_virtual'));
    s.useVirtualWrenches = f_virtual !== null;
    if (given) achdWasm.module.HEAPF64.set(given.values, at('qdd_given'));
    s._setPrescribedMask(given ? given.mask : new Array(nj).fill(false));
    s.numConstraints = nc;
    achdWasm.module._achd_solver_set_options(ptr, ...args);
    s.solve();
    return s.result();
  }
  // Runs fn(p, ...) with q read (once) and written at p, the double index of scratch
  // doubles: nq for q, then `extra`.
  _withQ(q, extra, fn) {
    const values = achdJointValues(q, 'q', this, true);
    const ptr = this._live();
    return achdWithScratch(values.length + extra, (p) => {
      achdWasm.module.HEAPF64.set(values, p);
      return fn(ptr, p);
    });
  }
  // [{name, position: [x, y, z], rotation: [9, row-major]}] per link after the root.
  forwardKinematics(q) {
    const nq = this.numPositions, nl = this.numLinks;
    return this._withQ(q, 12 * nl, (ptr, p) => {
      if (achdWasm.module._achd_robot_forward_kinematics(ptr, 8 * p, 8 * (p + nq))) throw achdLastError();
      return this.linkNames.map((name, l) => {
        const o = p + nq + 12 * l;
        return { name, position: Array.from(achdWasm.module.HEAPF64.subarray(o, o + 3)),
          rotation: Array.from(achdWasm.module.HEAPF64.subarray(o + 3, o + 12)) };
      });
    });
  }
  // 6 rows (linear first) of nj numbers: [v; w] of the tip link's origin = J qd.
  tipJacobian(q) {
    const nj = this.numJoints, nq = this.numPositions;
    return this._withQ(q, 6 * nj, (ptr, p) => {
      if (achdWasm.module._achd_robot_tip_jacobian(ptr, 8 * p, 8 * (p + nq))) throw achdLastError();
      return achdChunks(Array.from(achdWasm.module.HEAPF64.subarray(p + nq, p + nq + 6 * nj)), nj);
    });
  }
  // M(q) as nj rows, rotor inertia included unless {rotorInertia: false}.
  massMatrix(q, options) {
    const nj = this.numJoints, nq = this.numPositions;
    const o = achdOptionalObject(options, 'options', ['rotorInertia']);
    const rotor = o.rotorInertia === undefined ? true : o.rotorInertia;
    if (typeof rotor !== 'boolean') throw new Error('options.rotorInertia must be true or false');
    return this._withQ(q, nj * nj, (ptr, p) => {
      if (achdWasm.module._achd_robot_mass_matrix(ptr, 8 * p, rotor ? 1 : 0, 8 * (p + nq))) throw achdLastError();
      return achdChunks(Array.from(achdWasm.module.HEAPF64.subarray(p + nq, p + nq + nj * nj)), Math.max(nj, 1));
    });
  }
  // Inverse dynamics: the joint torques for (q, qd, qdd) under gravity and f_ext (each by
  // name or in model order, as in solve()).
  rnea(q, qd, qdd, options) {
    const nj = this.numJoints, nl = this.numLinks;
    const o = achdOptionalObject(options, 'options', ['gravity', 'f_ext', 'effects', 'frictionVelocity']);
    const k = achdConstants();
    const effects = achdEffectBits(o.effects, k.options.effects, 'options.effects');
    const fv = achdPositive(o.frictionVelocity, k.options.friction_velocity, 'options.frictionVelocity');
    const qdValues = achdJointValues(qd, 'qd', this), qddValues = achdJointValues(qdd, 'qdd', this);
    const gravity = achdReadNumbers(o.gravity === undefined ? k.case_gravity : o.gravity, 'gravity', 3);
    const f_ext = o.f_ext === undefined ? null : achdLinkWrenches(o.f_ext, this);
    const nq = this.numPositions;  // q first, then qd, qdd and the torques (nj each)
    return this._withQ(q, 3 * nj + 3 + 6 * nl, (ptr, p) => {
      const v = p + nq, g = v + 3 * nj, f = g + 3, heap = achdWasm.module.HEAPF64;
      heap.set(qdValues, v);
      heap.set(qddValues, v + nj);
      heap.set(gravity, g);
      if (f_ext) heap.set(f_ext, f);
      if (achdWasm.module._achd_robot_rnea(ptr, 8 * p, 8 * v, 8 * (v + nj), 8 * g,
        f_ext === null ? 0 : 8 * f, effects, fv, 8 * (v + 2 * nj))) throw achdLastError();
      return Array.from(achdWasm.module.HEAPF64.subarray(v + 2 * nj, v + 3 * nj));
    });
  }
  createSimulator(options) {
    if (options === undefined) options = {};  // (null: a named error)
    options = achdCheckObject(options, 'options', ['integrator', 'effects', 'gravity', 'limits',
      'frictionVelocity', 'stabilisationFrequency', 'stabilisationDamping', 'rtol', 'atol', 'policy',
      'singularRegion', 'maxDamping', 'jointControl']);
    // Defaults are achd::SimulatorOptions' (core/include/achd/simulator.hpp).
    const k = achdConstants(), d = k.simulator_options;
    let integratorName = options.integrator;
    if (Object.prototype.hasOwnProperty.call(ACHD_OLD_INTEGRATOR_NAMES, integratorName)) {
      achdDeprecated(`integrator '${integratorName}'`, `'${ACHD_OLD_INTEGRATOR_NAMES[integratorName]}'`);
      integratorName = ACHD_OLD_INTEGRATOR_NAMES[integratorName];
    }
    const integrator = achdChoice(integratorName, k.integrators, d.integrator, 'options.integrator');
    const effects = achdEffectBits(options.effects, d.effects, 'options.effects');
    const limits = achdChoice(options.limits, k.limit_policies, d.limits, 'options.limits');
    const frictionVelocity = achdPositive(options.frictionVelocity, d.solver.friction_velocity, 'options.frictionVelocity');
    const frequency = achdPositive(options.stabilisationFrequency, d.stabilisation_frequency, 'options.stabilisationFrequency');
    const damping = achdPositive(options.stabilisationDamping, d.stabilisation_damping, 'options.stabilisationDamping');
    const rtol = achdPositive(options.rtol, d.rtol, 'options.rtol');
    const atol = achdPositive(options.atol, d.atol, 'options.atol');
    const policy = achdChoice(options.policy, k.singularity_policies, d.solver.policy, 'options.policy');
    const singularRegion = achdPositive(options.singularRegion, d.solver.singular_region, 'options.singularRegion');
    const maxDamping = achdPositive(options.maxDamping, d.solver.max_damping, 'options.maxDamping');
    const gravity = options.gravity === undefined ? null : achdReadNumbers(options.gravity, 'gravity', 3);
    const jointControl = options.jointControl === undefined ? undefined
      : achdCheckObject(options.jointControl, 'options.jointControl', ['target', 'kp', 'kd', 'frequency', 'dampingRatio', 'feedforward']);
    // (the simulator starts at the zero pose: a target by default would be that)
    if (jointControl !== undefined && jointControl.target === undefined)
      throw new Error('options.jointControl.target is required (a pose as q)');
    const ptr = this._live();
    const create = (g) => achdWasm.module._achd_sim_create(ptr, integrator, effects, g, limits, frictionVelocity,
      frequency, damping, rtol, atol, policy, singularRegion, maxDamping);
    const sim = gravity === null ? create(0) : achdWithScratch(3, (p) => {
      achdWasm.module.HEAPF64.set(gravity, p);
      return create(8 * p);
    });
    if (!sim) throw achdLastError();
    const simulator = new Simulator(this, sim);
    // jointControl: as Simulator.setJointControl ({target, kp, kd} or {target, frequency,
    // dampingRatio, feedforward}), target required
    if (jointControl !== undefined) {
      try {
        simulator.setJointControl(jointControl);
      } catch (e) {
        simulator.delete();
        throw e;
      }
    }
    return simulator;
  }
}
