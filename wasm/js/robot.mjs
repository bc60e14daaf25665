// A loaded robot (achd.loadURDF): its description, solves and algorithms.
import { ACHD_OLD_INTEGRATOR_NAMES, achdConstants, achdDeprecated } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { ACHD_SOLVER_OPTION_KEYS, achdCheckObject, achdChoice, achdEffectBits, achdIsArrayLike, achdPositive, achdSolverOptions, achdWriteSpatialList, achdWriteVector } from './validation.mjs';
import { achdDriverWeights, achdJointValues, achdLinkWrenches, achdPrescribedJoints } from './case_names.mjs';
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
    const ptr = this._live();
    if (options === undefined || options === null) options = {};
    achdCheckObject(options, 'options', ACHD_SOLVER_OPTION_KEYS);
    const max = achdConstants().max_constraints;
    const mc = options.maxConstraints === undefined ? max : options.maxConstraints;
    if (!Number.isInteger(mc))
      throw new Error(`options.maxConstraints must be an integer in [0, ${max}], got ${mc}`);
    const args = achdSolverOptions(options);
    const s = achdWasm.module._achd_solver_create(ptr, mc);
    if (!s) throw achdLastError();
    achdWasm.module._achd_solver_set_options(s, ...args);
    return new Solver(this, s, mc);  // gravity: the C++ Case's default
  }
  // The case object in, the result object out (docs/design.md section 5; plain arrays:
  // copies). q, qd, ff_torques by joint name and f_ext, f_virtual by link name as in the
  // CLI; qdd_given by joint name or in model order (null: the torque is given); w_fext,
  // w_ff per tip column; constraints: blocks {link (a name), alpha, beta, point, w_fext, w_ff}.
  solve(c, options) {
    this._live();
    achdCheckObject(c, 'the case', ['q', 'qd', 'gravity', 'alpha', 'beta', 'f_ext', 'ff_torques', 'constraints',
      'qdd_given', 'w_fext', 'w_ff', 'f_virtual']);
    if (!('q' in c)) throw new Error("missing required field 'q'");
    if (!('gravity' in c)) throw new Error("missing required field 'gravity'");
    const args = achdSolverOptions(options);
    if (!this._solver) this._solver = this.createSolver();
    const s = this._solver, ptr = s._ptr, nj = this.numJoints, nl = this.numLinks;
    const names = s._bufferNames(), max = achdConstants().max_constraints;
    const at = (name) => achdWasm.module._achd_solver_buffer(ptr, names.indexOf(name)) >> 3;
    achdWriteVector(achdJointValues(c.q, 'q', this, true), 'q', this.numPositions, at('q'));
    achdWriteVector(c.gravity, 'gravity', 3, at('gravity'));
    if (c.qd === undefined) achdWasm.module.HEAPF64.fill(0, at('qd'), at('qd') + nj);
    else achdWriteVector(achdJointValues(c.qd, 'qd', this), 'qd', nj, at('qd'));
    if (c.ff_torques === undefined) achdWasm.module.HEAPF64.fill(0, at('ff_torques'), at('ff_torques') + nj);
    else achdWriteVector(achdJointValues(c.ff_torques, 'ff_torques', this), 'ff_torques', nj, at('ff_torques'));
    let nc = 0;
    if (c.alpha !== undefined) {
      if (!Array.isArray(c.alpha)) throw new Error('alpha must be an array of 6-element columns');
      if (c.alpha.length > max) throw new Error(`alpha: at most ${max} constraints, got ${c.alpha.length}`);
      nc = c.alpha.length;
      achdWriteSpatialList(c.alpha, 'alpha', nc, at('alpha'), 'columns');
    }
    if (c.beta !== undefined) {
      if (!achdIsArrayLike(c.beta)) throw new Error('beta must be an array of numbers');
      if (c.beta.length !== nc)
        throw new Error(`beta: expected ${nc} values (one per alpha column), got ${c.beta.length}`);
      achdWriteVector(c.beta, 'beta', nc, at('beta'));
    } else {
      achdWasm.module.HEAPF64.fill(0, at('beta'), at('beta') + nc);
    }
    for (const field of ['w_fext', 'w_ff'])
      achdWasm.module.HEAPF64.set(achdDriverWeights(c[field], field, nc), at(field));
    s.setConstraints(c.constraints === undefined ? [] : c.constraints);
    for (const field of ['f_ext', 'f_virtual']) {
      const on = c[field] !== undefined;
      if (on) {
        const wrenches = achdLinkWrenches(c[field], this, field);
        if (wrenches.length !== nl)
          throw new Error(`${field}: expected ${nl} wrenches (one per link after the root), got ${wrenches.length}`);
        achdWriteSpatialList(wrenches, field, nl, at(field), 'wrenches');
      }
      if (field === 'f_ext') s.useExternalWrenches = on;
      else s.useVirtualWrenches = on;
    }
    const given = c.qdd_given === undefined ? null : achdPrescribedJoints(c.qdd_given, this);
    if (given) achdWasm.module.HEAPF64.set(given.values, at('qdd_given'));
    s.setPrescribed(given ? given.mask : []);
    s.numConstraints = nc;
    achdWasm.module._achd_solver_set_options(ptr, ...args);
    s.solve();
    return s.result();
  }
  _q(q, p) { achdWriteVector(achdJointValues(q, 'q', this, true), 'q', this.numPositions, p); }
  // [{name, position: [x, y, z], rotation: [9, row-major]}] per link after the root.
  forwardKinematics(q) {
    const ptr = this._live(), nq = this.numPositions, nl = this.numLinks;
    return achdWithScratch(nq + 12 * nl, (p) => {
      this._q(q, p);
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
    const ptr = this._live(), nj = this.numJoints, nq = this.numPositions;
    return achdWithScratch(nq + 6 * nj, (p) => {
      this._q(q, p);
      if (achdWasm.module._achd_robot_tip_jacobian(ptr, 8 * p, 8 * (p + nq))) throw achdLastError();
      return achdChunks(Array.from(achdWasm.module.HEAPF64.subarray(p + nq, p + nq + 6 * nj)), nj);
    });
  }
  // M(q) as nj rows, rotor inertia included unless {rotorInertia: false}.
  massMatrix(q, options) {
    const ptr = this._live(), nj = this.numJoints;
    if (options === undefined) options = {};
    achdCheckObject(options, 'options', ['rotorInertia']);
    const rotor = options.rotorInertia === undefined ? true : options.rotorInertia;
    if (typeof rotor !== 'boolean') throw new Error('options.rotorInertia must be true or false');
    const nq = this.numPositions;
    return achdWithScratch(nq + nj * nj, (p) => {
      this._q(q, p);
      if (achdWasm.module._achd_robot_mass_matrix(ptr, 8 * p, rotor ? 1 : 0, 8 * (p + nq))) throw achdLastError();
      return achdChunks(Array.from(achdWasm.module.HEAPF64.subarray(p + nq, p + nq + nj * nj)), Math.max(nj, 1));
    });
  }
  // Inverse dynamics: the joint torques for (q, qd, qdd) under gravity and f_ext (each by
  // name or in model order, as in solve()).
  rnea(q, qd, qdd, options) {
    const ptr = this._live(), nj = this.numJoints, nl = this.numLinks;
    if (options === undefined) options = {};
    achdCheckObject(options, 'options', ['gravity', 'f_ext', 'effects', 'frictionVelocity']);
    const k = achdConstants();
    const effects = achdEffectBits(options.effects, k.options.effects, 'options.effects');
    const fv = achdPositive(options.frictionVelocity, k.options.friction_velocity, 'options.frictionVelocity');
    const nq = this.numPositions;  // q first, then qd, qdd and the torques (nj each)
    return achdWithScratch(nq + 3 * nj + 3 + 6 * nl, (p) => {
      const v = p + nq, g = v + 3 * nj, f = g + 3;
      this._q(q, p);
      achdWriteVector(achdJointValues(qd, 'qd', this), 'qd', nj, v);
      achdWriteVector(achdJointValues(qdd, 'qdd', this), 'qdd', nj, v + nj);
      achdWriteVector(options.gravity === undefined ? k.case_gravity : options.gravity, 'gravity', 3, g);
      if (options.f_ext !== undefined) {
        const f_ext = achdLinkWrenches(options.f_ext, this);
        if (f_ext.length !== nl)
          throw new Error(`f_ext: expected ${nl} wrenches (one per link after the root), got ${f_ext.length}`);
        achdWriteSpatialList(f_ext, 'f_ext', nl, f, 'wrenches');
      }
      if (achdWasm.module._achd_robot_rnea(ptr, 8 * p, 8 * v, 8 * (v + nj), 8 * g,
        options.f_ext === undefined ? 0 : 8 * f, effects, fv, 8 * (v + 2 * nj))) throw achdLastError();
      return Array.from(achdWasm.module.HEAPF64.subarray(v + 2 * nj, v + 3 * nj));
    });
  }
  createSimulator(options) {
    const ptr = this._live();
    if (options === undefined || options === null) options = {};
    achdCheckObject(options, 'options', ['integrator', 'effects', 'gravity', 'limits',
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
    const create = (gravity) => achdWasm.module._achd_sim_create(ptr, integrator, effects, gravity, limits, frictionVelocity,
      frequency, damping, rtol, atol, policy, singularRegion, maxDamping);
    const sim = options.gravity === undefined ? create(0) : achdWithScratch(3, (p) => {
      achdWriteVector(options.gravity, 'gravity', 3, p);
      return create(8 * p);
    });
    if (!sim) throw achdLastError();
    const simulator = new Simulator(this, sim);
    // jointControl: as Simulator.setJointControl ({target, kp, kd} or {target, frequency,
    // dampingRatio, feedforward}), target required
    if (options.jointControl !== undefined) {
      try {
        achdCheckObject(options.jointControl, 'options.jointControl', ['target', 'kp', 'kd', 'frequency', 'dampingRatio', 'feedforward']);
        // (the simulator starts at the zero pose: a target by default would be that)
        if (options.jointControl.target === undefined) throw new Error('options.jointControl.target is required (a pose as q)');
        simulator.setJointControl(options.jointControl);
      } catch (e) {
        simulator.delete();
        throw e;
      }
    }
    return simulator;
  }
}
