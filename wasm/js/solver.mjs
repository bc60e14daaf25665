// The zero-copy solver (robot.createSolver).
import { achdConstants } from './constants.mjs';
import { achdLastError, achdSigmaMin, achdWasm } from './runtime.mjs';
import { achdDescribe, achdReadArray, achdSolverOptions } from './validation.mjs';
import { achdResultOf, achdWithScratch, achdWithString } from './memory.mjs';
import { achdJsonText } from './json_text.mjs';
import { AchdHandle } from './handle.mjs';

// The zero-copy solver: write the views, call solve(), read the views.
export class Solver extends AchdHandle {
  // The old name of numRates, kept for one release: it counted joint rates (a floating
  // base's free joint 6), not joints.
  /** @deprecated numRates */
  get numJoints() { return this.numRates; }

  constructor(robot, ptr, maxConstraints) {
    super('Solver', ptr, achdWasm.module._achd_solver_delete);
    this.numRates = robot.numRates;
    this.numLinks = robot.numLinks;
    this.maxConstraints = maxConstraints;
    this.numPositions = robot.numPositions;
    this._joints = robot.joints;  // their rates, for setPrescribed by name
    this._couplings = robot.couplings.length;
    this._nc = 0;
    this._blocks = 0;
    this._blockColumns = 0;
    this._external = false;
    this._virtual = false;
    this._prescribed = new Array(robot.numRates).fill(false);
  }
  _bufferOf(ptr, index) { return achdWasm.module._achd_solver_buffer(ptr, index); }
  _bufferNames() { return achdConstants().solver_buffers; }
  _layout() {
    const nj = this.numRates, nl = this.numLinks, mc = this.maxConstraints;
    return [['q', this.numPositions], ['qd', nj], ['ff_torques', nj], ['gravity', 3], ['alpha', 6 * mc], ['beta', mc],
      ['f_ext', 6 * nl], ['qdd', nj], ['nu', this._nc + this._blockColumns], ['joint_torques', nj], ['constraint_torques', nj],
      ['total_torques', nj], ['link_accelerations', 6 * (nl + 1)], ['constraint_wrench', 6],
      ['constraint_wrenches', 6 * this._blocks], ['qdd_given', nj], ['w_fext', mc], ['w_ff', mc],
      ['f_virtual', 6 * nl], ['prescribed_torques', nj], ['virtual_torques', nj],
      ['coupling_forces', this._couplings]];
  }
  get q() { return this._view('q'); }
  get qd() { return this._view('qd'); }
  get ff_torques() { return this._view('ff_torques'); }
  get gravity() { return this._view('gravity'); }
  get alpha() { return this._view('alpha'); }
  get beta() { return this._view('beta'); }
  get f_ext() { return this._view('f_ext'); }
  get qdd() { return this._view('qdd'); }
  get nu() { return this._view('nu'); }
  get joint_torques() { return this._view('joint_torques'); }
  get constraint_torques() { return this._view('constraint_torques'); }
  get total_torques() { return this._view('total_torques'); }
  get link_accelerations() { return this._view('link_accelerations'); }
  get constraint_wrench() { return this._view('constraint_wrench'); }
  get constraint_wrenches() { return this._view('constraint_wrenches'); }
  // The drivers: the prescribed joints' accelerations (read for the joints
  // setPrescribed names), the tip columns' driver weights (1 until written; the first
  // numConstraints are used), the virtual wrenches (read while useVirtualWrenches), and
  // their results.
  get qdd_given() { return this._view('qdd_given'); }
  get w_fext() { return this._view('w_fext'); }
  get w_ff() { return this._view('w_ff'); }
  get f_virtual() { return this._view('f_virtual'); }
  get prescribed_torques() { return this._view('prescribed_torques'); }
  get virtual_torques() { return this._view('virtual_torques'); }
  // Coupled joints (robot.couplings): their forces nu_c, one per coupling, after a solve.
  get coupling_forces() { return this._view('coupling_forces'); }
  get rank() { return achdWasm.module._achd_solver_rank(this._live()); }
  get sigma_min() { return achdSigmaMin(this._live()); }
  // Blocks whose columns give way to the joints' efforts (a block's yields): the largest
  // |tau_i| / effort_i of the solve that follows them, and how far the last solve gave
  // them up (0: followed, 1: wholly; both 0 without such columns or outside variable_damping).
  get effort_ratio() { return achdWasm.module._achd_solver_effort_ratio(this._live()); }
  get yielded() { return achdWasm.module._achd_solver_yielded(this._live()); }
  get numConstraints() { this._live(); return this._nc; }
  set numConstraints(nc) {
    // (the range is checked here too: C++ takes an int, which would wrap 2**31)
    if (!Number.isInteger(nc) || nc < 0 || nc > this.maxConstraints)
      throw new Error(`numConstraints must be an integer in [0, ${this.maxConstraints}] (maxConstraints), got ${achdDescribe(nc)}`);
    if (achdWasm.module._achd_solver_set_num_constraints(this._live(), nc)) throw achdLastError();
    this._nc = nc;
    this._buffer = null;  // the nu view's length changed
  }
  // Constraint blocks on links, [{link (a name), alpha: [6-vectors], beta, point, link_b,
  // point_b, w_fext, w_ff}], for the solves that follow, after the tip's numConstraints columns in nu: a
  // case's "constraints", parsed by the C++ case parser from the bridge's JSON text and
  // copied into the solver's storage, so a solve never allocates.
  setConstraints(blocks) {
    const text = achdJsonText(blocks);
    const ptr = this._live();
    achdWithString(text, (p) => {
      if (achdWasm.module._achd_solver_set_constraints(ptr, p)) throw achdLastError();
    });
    this._blocks = achdWasm.module._achd_solver_num_blocks(ptr);
    this._blockColumns = achdWasm.module._achd_solver_block_columns(ptr);
    this._buffer = null;  // the nu and constraint_wrenches views' lengths changed
  }
  get numBlocks() { this._live(); return this._blocks; }
  get useExternalWrenches() { this._live(); return this._external; }
  set useExternalWrenches(on) {
    if (typeof on !== 'boolean') throw new Error('useExternalWrenches must be true or false');
    achdWasm.module._achd_solver_use_external_wrenches(this._live(), on ? 1 : 0);
    this._external = on;
  }
  get useVirtualWrenches() { this._live(); return this._virtual; }
  set useVirtualWrenches(on) {
    if (typeof on !== 'boolean') throw new Error('useVirtualWrenches must be true or false');
    achdWasm.module._achd_solver_use_virtual_wrenches(this._live(), on ? 1 : 0);
    this._virtual = on;
  }
  // The joints whose acceleration is given (the qdd_given view) instead of their torque:
  // joint names (a floating base's free joint: its six rates), or one boolean per joint
  // rate in model order; [] for none.
  setPrescribed(joints) {
    const nj = this.numRates;
    const list = achdReadArray(joints, 'setPrescribed', 'an array of joint names or of booleans');
    const mask = new Array(nj).fill(false);
    if (list.length && typeof list[0] === 'boolean') {
      if (list.length !== nj) throw new Error(`setPrescribed: expected ${nj} booleans (one per joint), got ${list.length}`);
      list.forEach((on, i) => {
        if (typeof on !== 'boolean') throw new Error(`setPrescribed: entry ${i} must be true or false, got ${achdDescribe(on)}`);
        mask[i] = on;
      });
    } else {
      list.forEach((name, i) => {
        if (typeof name !== 'string') throw new Error(`setPrescribed: entry ${i} must be a joint name, got ${achdDescribe(name)}`);
        const joint = this._joints.find((j) => j.name === name);
        if (!joint) throw new Error(`setPrescribed: ${this._noJoint(name)}`);
        mask.fill(true, joint.rateIndex, joint.rateIndex + joint.rateCount);
      });
    }
    this._setPrescribedMask(mask);
  }
  // One boolean per joint rate (checked) into the solver.
  _setPrescribedMask(mask) {
    const ptr = this._live();
    achdWithScratch(Math.max(mask.length, 1), (p) => {
      achdWasm.module.HEAPF64.set(mask.map((on) => (on ? 1 : 0)), p);
      achdWasm.module._achd_solver_set_prescribed(ptr, 8 * p);
    });
    this._prescribed = mask;
  }
  get prescribed() { this._live(); return this._prescribed.slice(); }
  // Why `name` names none of the model's movable joints, in the case parser's words.
  _noJoint(name) {
    const ptr = this._live();
    return achdWithString(name, (p) => achdWasm.text.UTF8ToString(achdWasm.module._achd_solver_no_joint(ptr, p)));
  }
  setOptions(options) {
    const args = achdSolverOptions(options);
    achdWasm.module._achd_solver_set_options(this._live(), ...args);
  }
  // hybrid_dynamics on the views, in place: no allocation, no copy.
  solve() {
    if (achdWasm.module._achd_solver_solve(this._ptr === 0 ? this._live() : this._ptr)) throw achdLastError();
  }
  // The outputs of the last solve as plain arrays (the result object of docs/design.md
  // section 5, as robot.solve() and the CLI give it; a copy).
  result() {
    return achdResultOf(achdWasm.module._achd_solver_result(this._live()));
  }
}
