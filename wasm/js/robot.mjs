// A loaded robot (achd.loadURDF): its description, solves and algorithms.
import { ACHD_OLD_INTEGRATOR_NAMES, achdConstants, achdDeepFreeze, achdDeprecated } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { ACHD_SOLVER_OPTION_KEYS, achdCheckObject, achdChoice, achdDescribe, achdEffectBits, achdOptionalObject, achdPositive, achdReadNumbers, achdSolverOptions } from './validation.mjs';
import { achdJsonText } from './json_text.mjs';
import { achdChunks, achdResultOf, achdWithScratch, achdWithString } from './memory.mjs';
import { AchdHandle } from './handle.mjs';
import { Solver } from './solver.mjs';
import { Simulator } from './simulator.mjs';

export class Robot extends AchdHandle {
  // The old name of numRates, kept for one release: it counted joint rates (a floating
  // base's free joint 6), not joints.
  /** @deprecated numRates */
  get numJoints() { return this.numRates; }

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
    // Loop joints (options.loops): [{name, type, link_a, link_b, directions, dropped}], the
    // directions of each loop frame held in every solve (after the case's blocks in nu) and
    // those found held by the tree already.
    this.loops = info.loops;
    // With a floating base (options.floating) the free joint comes first in jointNames, named
    // after the root link, with 7 of the numPositions numbers of q and 6 of the numRates
    // numbers of qd, qdd and the torques; without one both counts are the joints'.
    this.floating = info.floating;
    this.numRates = info.num_rates;
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
    // Each joint's numbers: {name, type, rateIndex, rateCount (in qd, qdd and the torques),
    // positionIndex, positionCount (in q)}; a floating base's free joint has 6 rates and 7
    // positions, every other joint one of each.
    this.joints = achdDeepFreeze(info.joints.map((j) => ({ name: j.name, type: j.type, rateIndex: j.rate_index,
      rateCount: j.rate_count, positionIndex: j.position_index, positionCount: j.position_count })));
    // The links the robot carries, as its URDF has them (wasm/src/robot_links.hpp): the
    // root, the links of linkNames, then the links merged into a body without being links
    // of the model (a chain's side branches), each {name, frame (0: the root, 1 + its index
    // in linkNames; a merged link: the link it rides on), parent (link name; null for the
    // root), joint ({name, type} of the URDF joint above it, or null), body (the joint
    // whose body it rides on, null: fixed to the root), mass (its own), offset (a merged
    // link's pose in its frame's link, {position, rotation}, else null), visuals: [{position,
    // rotation (in the link's frame, rotation row-major), geometry, color}]}.
    this.links = achdDeepFreeze(info.link_details);
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
  // copies). The case is the CLI's: written as JSON text by the bridge (json_text.mjs,
  // read once, what JSON cannot hold marked) and parsed, checked and solved by C++ with
  // the CLI's case parser, whose messages name the field and the index; the result is
  // the CLI's result JSON, each number in the fewest digits that read back as it (the
  // same doubles as the CLI's 17 digits).
  solve(c, options) {
    this._live();
    const args = achdSolverOptions(options);
    const text = achdJsonText(c);
    const ptr = this._live();  // (a Proxy's trap may have deleted the robot meanwhile)
    return achdResultOf(achdWithString(text, (p) => achdWasm.module._achd_robot_solve(ptr, p, ...args)));
  }
  // A case-shaped input (q by joint name or in model order, f_ext by link name, ...) of
  // `kind` (achd.constants.input_kinds) read by the C++ case parser from the bridge's
  // JSON text: a Float64Array of n numbers.
  _readInput(value, field, kind, n) {
    const text = achdJsonText(value), which = achdConstants().input_kinds.indexOf(kind);
    const ptr = this._live();
    return achdWithString(text, (t) => achdWithString(field, (f) => achdWithScratch(n, (p) => {
      if (achdWasm.module._achd_robot_read_input(ptr, t, f, which, 8 * p)) throw achdLastError();
      return achdWasm.module.HEAPF64.slice(p, p + n);
    })));
  }
  // Runs fn(p, ...) with q read (once) and written at p, the double index of scratch
  // doubles: nq for q, then `extra`.
  _withQ(q, extra, fn) {
    const values = this._readInput(q, 'q', 'joint_positions', this.numPositions);
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
    const nj = this.numRates, nq = this.numPositions;
    return this._withQ(q, 6 * nj, (ptr, p) => {
      if (achdWasm.module._achd_robot_tip_jacobian(ptr, 8 * p, 8 * (p + nq))) throw achdLastError();
      return achdChunks(Array.from(achdWasm.module.HEAPF64.subarray(p + nq, p + nq + 6 * nj)), nj);
    });
  }
  // M(q) as nj rows, rotor inertia included unless {rotorInertia: false}.
  massMatrix(q, options) {
    const nj = this.numRates, nq = this.numPositions;
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
    const nj = this.numRates, nl = this.numLinks;
    const o = achdOptionalObject(options, 'options', ['gravity', 'f_ext', 'effects', 'frictionVelocity']);
    const k = achdConstants();
    const effects = achdEffectBits(o.effects, k.options.effects, 'options.effects');
    const fv = achdPositive(o.frictionVelocity, k.options.friction_velocity, 'options.frictionVelocity');
    const qdValues = this._readInput(qd, 'qd', 'joint_rates', nj), qddValues = this._readInput(qdd, 'qdd', 'joint_rates', nj);
    const gravity = this._readInput(o.gravity === undefined ? k.case_gravity : o.gravity, 'gravity', 'vector3', 3);
    const f_ext = o.f_ext === undefined ? null : this._readInput(o.f_ext, 'f_ext', 'link_wrenches', 6 * nl);
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
