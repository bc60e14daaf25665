// The simulator (robot.createSimulator).
import { achdConstants, achdDeprecated } from './constants.mjs';
import { achdLastError, achdWasm } from './runtime.mjs';
import { achdCheckObject, achdDescribe, achdOptionalObject, achdReadNumbers } from './validation.mjs';
import { achdCopy, achdWithScratch } from './memory.mjs';
import { AchdHandle } from './handle.mjs';

// by default (about 0.1 s of the 7-DoF arm with RK4).
export const ACHD_MAX_RUN_CHUNK = 2 ** 30;
export const ACHD_PROGRESS_INTERVAL = 10000;

// A link or joint reference for a message: a name in double quotes, anything else by
// achdDescribe (no toJSON or toString of the caller's runs).
function achdShowRef(x) {
  return typeof x === 'string' ? JSON.stringify(x) : achdDescribe(x);
}

// Time stepping; q, qd, ff_torques, f_ext are views on the simulator's state.
export class Simulator extends AchdHandle {
  // The old name of numRates, kept for one release: it counted joint rates (a floating
  // base's free joint 6), not joints.
  /** @deprecated numRates */
  get numJoints() { return this.numRates; }

  constructor(robot, ptr) {
    super('Simulator', ptr, achdWasm.module._achd_sim_delete);
    this.numRates = robot.numRates;
    this.numPositions = robot.numPositions;  // q's length (7 + joints with a floating base)
    this.numLinks = robot.numLinks;
    this._robot = robot;
    this._linkNames = robot.linkNames;
    this._jointNames = robot.jointNames;
    this._resets = 0;         // reset() calls, for step() to see one made by its onProgress
    this._stepping = false;   // inside step() (its onProgress may call back)
  }
  _bufferOf(ptr, index) { return achdWasm.module._achd_sim_buffer(ptr, index); }
  _bufferNames() { return achdConstants().simulator_buffers; }
  _layout() {
    return [['q', this.numPositions], ['qd', this.numRates], ['t', 1], ['ff_torques', this.numRates],
      ['f_ext', 6 * this.numLinks]];
  }
  get q() { return this._view('q'); }
  get qd() { return this._view('qd'); }
  get ff_torques() { return this._view('ff_torques'); }
  get f_ext() { return this._view('f_ext'); }
  get t() { return this._ownView('t')[0]; }
  // n steps of dt (n up to 2^53 - 1), given to wasm in chunks (its run() takes an int);
  // with options.onProgress, chunks of options.progressInterval steps, after each of
  // which onProgress(stepsDone, n) is called: returning false stops the run. Returns the
  // number of steps run. A failed step throws (the state stays at the last good step).
  // onProgress may change directions, controls and wrenches (the next chunk uses them);
  // if it deletes or resets this simulator the run stops with an Error saying so, and a
  // step() inside it is refused.
  step(n = 1, dt = 1e-3, options = undefined) {
    this._live();
    if (this._stepping) throw new Error('Simulator.step: called from its own onProgress callback (step() does not nest)');
    if (!Number.isSafeInteger(n) || n < 0)
      throw new Error(`step: n must be an integer >= 0 and <= 2^53 - 1, got ${achdDescribe(n)}`);
    if (typeof dt !== 'number' || !Number.isFinite(dt) || dt <= 0)
      throw new Error(`step: dt must be a finite number > 0, got ${achdDescribe(dt)}`);
    const o = achdOptionalObject(options, 'step options', ['onProgress', 'progressInterval']);
    const onProgress = o.onProgress;
    if (onProgress !== undefined && typeof onProgress !== 'function')
      throw new Error('step options.onProgress must be a function (stepsDone, total) => boolean');
    const interval = o.progressInterval === undefined ? ACHD_PROGRESS_INTERVAL : o.progressInterval;
    if (!Number.isSafeInteger(interval) || interval < 1)
      throw new Error(`step options.progressInterval must be an integer >= 1, got ${achdDescribe(interval)}`);
    const chunk = Math.min(onProgress ? interval : ACHD_MAX_RUN_CHUNK, ACHD_MAX_RUN_CHUNK);
    const ptr = this._live(), resets = this._resets;
    let done = 0;
    this._stepping = true;
    try {
      while (done < n) {
        const k = Math.min(chunk, n - done);
        if (achdWasm.module._achd_sim_run(ptr, k, dt)) throw achdLastError();
        done += k;
        if (!onProgress) continue;
        const more = onProgress(done, n);
        // The callback ran the caller's code: the pointer is used again only if it is
        // still this simulator's, in the state this run left it.
        if (this._ptr !== ptr)
          throw new Error(`Simulator.step: the onProgress callback deleted the simulator (after ${done} of ${n} steps)`);
        if (this._resets !== resets)
          throw new Error(`Simulator.step: the onProgress callback reset the simulator (after ${done} of ${n} steps); the run stops there`);
        if (more === false) break;
      }
    } finally {
      this._stepping = false;
    }
    return done;
  }
  // Steps completed since createSimulator() or reset().
  get stepsTaken() { return achdWasm.module._achd_sim_steps_taken(this._live()); }
  // The integrator's substeps accepted and rejected since createSimulator() or reset()
  // (a fixed-step integrator: one per step, none rejected).
  get substeps() { return achdWasm.module._achd_sim_substeps(this._live()); }
  get rejectedSubsteps() { return achdWasm.module._achd_sim_rejected_substeps(this._live()); }
  get stiffSubsteps() { return achdWasm.module._achd_sim_stiff_substeps(this._live()); }
  reset(q, qd) {
    const n = this.numRates, nq = this.numPositions;
    const q0 = achdReadNumbers(q, 'q', nq), qd0 = qd === undefined ? new Float64Array(n) : achdReadNumbers(qd, 'qd', n);
    const ptr = this._live();
    achdWithScratch(nq + n, (p) => {
      achdWasm.module.HEAPF64.set(q0, p);
      achdWasm.module.HEAPF64.set(qd0, p + nq);
      if (achdWasm.module._achd_sim_reset(ptr, 8 * p, 8 * (p + nq))) throw achdLastError();
    });
    ++this._resets;
    this._buffer = null;  // reset() may have given q and qd new buffers
  }
  // The directions act on a link: `link` a link name or index (linkNames), or omitted
  // for a chain's tip (an error on a tree). Each link has its own set; its constraint
  // block comes in nu in the order the links were first given directions (directionLinks()).
  _linkIndex(link, what) {
    if (link === undefined || link === null) return -1;
    const index = typeof link === 'string' ? this._linkNames.indexOf(link) : link;
    if (!Number.isInteger(index) || index < 0 || index >= this.numLinks)
      throw new Error(`${what}: unknown link ${achdShowRef(link)} (index 0..${this.numLinks - 1} or a link name)`);
    return index;
  }
  _directionIndex(name, what) {
    const directions = achdConstants().directions, index = directions.indexOf(name);
    if (index < 0) throw new Error(`${what}: unknown direction '${name}' (${directions.join(', ')})`);
    return index;
  }
  // name: x y z rx ry rz; mode: 'hold', 'free' or a number (classical acceleration setpoint).
  setDirection(name, mode, link) {
    const ptr = this._live(), modes = achdConstants().direction_modes;
    const index = this._directionIndex(name, 'setDirection'), l = this._linkIndex(link, 'setDirection');
    let code, setpoint = 0;
    if (mode === 'free' || mode === 'hold') code = modes.indexOf(mode);
    else if (typeof mode === 'number' && Number.isFinite(mode)) { code = modes.indexOf('accelerate'); setpoint = mode; }
    else throw new Error(`setDirection: mode must be 'hold', 'free' or a finite number, got ${achdDescribe(mode)}`);
    if (achdWasm.module._achd_sim_set_direction(ptr, l, index, code, setpoint)) throw achdLastError();
  }
  // The mode of a direction: 'free', 'hold' or 'accelerate'.
  directionMode(name, link) {
    const ptr = this._live(), index = this._directionIndex(name, 'directionMode'), l = this._linkIndex(link, 'directionMode');
    const mode = achdWasm.module._achd_sim_direction_mode(ptr, l, index);
    if (mode < 0) throw achdLastError();
    return achdConstants().direction_modes[mode];
  }
  // Driver priorities of a direction, each in [0, 1] (default 1): how far it resists the
  // external wrenches (wFext) and the feed-forward torques (wFf). A held direction with a
  // weight below 1 yields to that driver and is re-anchored where its point is every step.
  // weights: {wFext, wFf} (each omitted: 1).
  setDirectionWeights(name, weights, link = undefined) {
    const w = achdOptionalObject(weights, 'setDirectionWeights: weights {wFext, wFf}', ['wFext', 'wFf']);
    const weight = (key) => {
      const x = w[key] === undefined ? 1 : w[key];
      if (typeof x !== 'number') throw new Error(`setDirectionWeights: ${key} must be a number in [0, 1], got ${achdDescribe(x)}`);
      return x;  // (the range and NaN: the C++ check's message)
    };
    const wFext = weight('wFext'), wFf = weight('wFf');
    const ptr = this._live(), index = this._directionIndex(name, 'setDirectionWeights');
    const l = this._linkIndex(link, 'setDirectionWeights');
    if (achdWasm.module._achd_sim_set_direction_weights(ptr, l, index, wFext, wFf)) throw achdLastError();
  }
  // Where a link's directions act: [x, y, z] in the link's frame (default its origin); its
  // held directions are re-anchored there.
  setDirectionPoint(link, point) {
    const l = this._linkIndex(link, 'setDirectionPoint');
    if (l < 0) throw new Error('setDirectionPoint: name the link');
    const at = achdReadNumbers(point, 'point', 3);
    const ptr = this._live();
    achdWithScratch(3, (p) => {
      achdWasm.module.HEAPF64.set(at, p);
      if (achdWasm.module._achd_sim_set_direction_point(ptr, l, 8 * p)) throw achdLastError();
    });
  }
  // The links that have directions, in the order of their blocks in nu, with the number
  // of active directions of each: [{link, directions}] (a link with 0 has no block).
  directionLinks() {
    const ptr = this._live(), n = achdWasm.module._achd_sim_direction_sets(ptr, 0);
    return achdWithScratch(n, (p) => {
      achdWasm.module._achd_sim_direction_sets(ptr, 8 * p);
      const h = achdWasm.module.HEAP32;
      return Array.from({ length: n }, (_, i) => ({ link: this._linkNames[h[2 * p + 2 * i]], directions: h[2 * p + 2 * i + 1] }));
    });
  }
  // The joint PD controller: every solve adds kp (target - q) - kd qd to ff_torques.
  // target: a pose as q (numPositions numbers, default the current q); kp, kd: one number
  // for every joint (0 on a floating base's free joint) or numRates numbers.
  // Or gains from frequency (Hz) and dampingRatio (default 1), and feedforward 'hold'
  // (JointControl in C++).
  setJointControl(control) {
    const c = achdOptionalObject(control, 'setJointControl: the control {target, kp, kd} or {target, frequency, dampingRatio, feedforward}',
      ['target', 'kp', 'kd', 'frequency', 'dampingRatio', 'feedforward']);
    const n = this.numRates, nq = this.numPositions;
    const byFrequency = c.frequency !== undefined;
    if (byFrequency && (c.kp !== undefined || c.kd !== undefined))
      throw new Error('setJointControl: give kp and kd, or frequency and dampingRatio, not both');
    if (!byFrequency && c.kp === undefined) throw new Error('setJointControl: kp (or frequency) is required');
    const dampingRatio = c.dampingRatio === undefined ? 1 : c.dampingRatio;
    for (const [x, name] of [[c.frequency, 'frequency'], [dampingRatio, 'dampingRatio']])
      if (byFrequency && typeof x !== 'number') throw new Error(`setJointControl: ${name} must be a number, got ${achdDescribe(x)}`);
    const feedforward = c.feedforward === undefined ? 'none' : c.feedforward;
    if (feedforward !== 'hold' && feedforward !== 'none')
      throw new Error(`setJointControl: feedforward: expected 'hold' or 'none', got ${achdDescribe(feedforward)}`);
    const gains = (g, name) => {
      if (typeof g === 'number') {
        const out = new Float64Array(n).fill(g);
        if (this._robot.floating) out.fill(0, 0, 6);
        return out;
      }
      return achdReadNumbers(g, `setJointControl: ${name}`, n);
    };
    const kpv = byFrequency ? null : gains(c.kp, 'kp'), kdv = byFrequency ? null : gains(c.kd === undefined ? 0 : c.kd, 'kd');
    const target = c.target === undefined ? null : achdReadNumbers(c.target, 'setJointControl: target', nq);
    const ptr = this._live();
    achdWithScratch(nq + 2 * n, (p) => {
      const heap = achdWasm.module.HEAPF64;
      heap.set(target === null ? this._ownView('q') : target, p);
      if (!byFrequency) {
        heap.set(kpv, p + nq);
        heap.set(kdv, p + nq + n);
      }
      const kpPtr = byFrequency ? 0 : 8 * (p + nq), kdPtr = byFrequency ? 0 : 8 * (p + nq + n);
      if (achdWasm.module._achd_sim_set_joint_control(ptr, 8 * p, kpPtr, kdPtr, byFrequency ? c.frequency : 0,
        byFrequency ? dampingRatio : 0, feedforward === 'hold' ? 1 : 0)) throw achdLastError();
    });
  }
  clearJointControl() { achdWasm.module._achd_sim_clear_joint_control(this._live()); }
  get jointControlOn() { return achdWasm.module._achd_sim_joint_control_on(this._live()) !== 0; }
  // Prescribed joint motion: joint (a name or an index) follows {motion: 'constant' |
  // 'ramp' | 'sine', position, velocity, amplitude, frequency, phase} (parameters its
  // kind does not read: absent) in the simulated time, put on it at once; release(joint)
  // drives it by its torques again. reset() releases every joint.
  prescribe(joint, motion) {
    const index = this._jointIndex(joint, 'prescribe');
    motion = achdCheckObject(motion, 'prescribe: motion', ['motion', 'position', 'velocity', 'amplitude', 'frequency', 'phase']);
    const kinds = achdConstants().motion_kinds, kind = kinds.indexOf(motion.motion);
    if (kind < 0)
      throw new Error(`prescribe: motion.motion: expected ${kinds.map((k) => `'${k}'`).join(', ')}, got '${motion.motion}'`);
    const value = (key) => {
      const x = motion[key] === undefined ? 0 : motion[key];
      if (typeof x !== 'number') throw new Error(`prescribe: motion.${key} must be a number, got ${achdDescribe(x)}`);
      return x;
    };
    const position = value('position'), velocity = value('velocity'), amplitude = value('amplitude');
    const frequency = value('frequency'), phase = value('phase');
    if (achdWasm.module._achd_sim_prescribe(this._live(), index, kind, position, velocity, amplitude, frequency, phase))
      throw achdLastError();
  }
  release(joint) {
    const ptr = this._live(), index = this._jointIndex(joint, 'release');
    if (achdWasm.module._achd_sim_release(ptr, index)) throw achdLastError();
  }
  // Names of the prescribed joints, root to tip.
  prescribedJoints() {
    const ptr = this._live();
    return this._jointNames.filter((name, i) =>
      (!this._robot.floating || i > 0) && achdWasm.module._achd_sim_prescribed(ptr, this._rateIndex(i)) !== 0);
  }
  // jointNames index -> the joint's entry in qd (behind a floating base's six rates).
  _rateIndex(i) { return this._robot.floating && i > 0 ? i + 5 : i; }
  _jointIndex(joint, what) {
    const index = typeof joint === 'string' ? this._rateIndex(this._jointNames.indexOf(joint)) : joint;
    if (!Number.isInteger(index) || index < 0 || index >= this.numRates)
      throw new Error(`${what}: unknown joint ${achdShowRef(joint)} (index 0..${this.numRates - 1} or a joint name)`);
    return index;
  }
  // Held-direction residuals (m or rad) of a link (omitted: the tip); null for directions
  // that are not held (free or accelerated: neither has a position or angle to keep).
  residuals(link) {
    const ptr = this._live(), l = this._linkIndex(link, 'residuals');
    const directions = achdConstants().directions, hold = achdConstants().direction_modes.indexOf('hold');
    return achdWithScratch(directions.length, (p) => {
      if (achdWasm.module._achd_sim_residuals(ptr, l, 8 * p)) throw achdLastError();
      const out = {};
      directions.forEach((name, k) => {
        out[name] = achdWasm.module._achd_sim_direction_mode(ptr, l, k) === hold ? achdWasm.module.HEAPF64[p + k] : null;
      });
      return out;
    });
  }
  // The constraint wrench of each link with active directions in the last solve (copies):
  // {link name: [fx, fy, fz, tx, ty, tz]}, alpha nu at the link's point, base axes: what
  // the link exerts on its constraint.
  constraintWrenches() {
    const ptr = this._live(), n = achdWasm.module._achd_sim_constraint_wrenches(ptr, 0);
    const links = this.directionLinks().filter((s) => s.directions > 0);
    return achdWithScratch(6 * n, (p) => {
      achdWasm.module._achd_sim_constraint_wrenches(ptr, 8 * p);
      const out = {};
      // defineProperty: a link named '__proto__' is a key like the others, not the prototype
      for (let b = 0; b < links.length; ++b) {  // (the loop joints' blocks follow)
        Object.defineProperty(out, links[b].link, { value: Array.from(achdWasm.module.HEAPF64.subarray(p + 6 * b, p + 6 * b + 6)),
          enumerable: true, writable: true, configurable: true });
      }
      return out;
    });
  }
  // Each loop joint's closure error (robot.loops: m or rad, the largest over its held
  // directions): {loop name: {now, max}}, max the largest since reset().
  loopDrift() {
    const ptr = this._live(), out = {};
    this._robot.loops.forEach((loop, l) => {
      const now = achdWasm.module._achd_sim_loop_error(ptr, l, 0), max = achdWasm.module._achd_sim_loop_error(ptr, l, 1);
      if (Number.isNaN(now) || Number.isNaN(max)) throw achdLastError();
      Object.defineProperty(out, loop.name, { value: { now, max }, enumerable: true, writable: true, configurable: true });
    });
    return out;
  }
  // How long (s) each direction of each loop joint (of its loop frame) was released since
  // reset(): {loop name: {x, y, z, rx, ry, rz}}.
  loopReleasedSeconds() {
    const ptr = this._live(), out = {}, directions = achdConstants().directions;
    this._robot.loops.forEach((loop, l) => {
      const seconds = achdWithScratch(directions.length, (p) => {
        if (achdWasm.module._achd_sim_loop_released_seconds(ptr, l, 8 * p)) throw achdLastError();
        return Object.fromEntries(directions.map((name, k) => [name, achdWasm.module.HEAPF64[p + k]]));
      });
      Object.defineProperty(out, loop.name, { value: seconds, enumerable: true, writable: true, configurable: true });
    });
    return out;
  }
  energy() {
    const ptr = this._live();
    const kinetic = achdWasm.module._achd_sim_kinetic_energy(ptr), potential = achdWasm.module._achd_sim_potential_energy(ptr);
    return { kinetic, potential, total: kinetic + potential };
  }
  // Names of the joints at or past a limit after the last step (a copy; [] under 'ignore').
  limitHits() {
    const ptr = this._live(), n = achdWasm.module._achd_sim_limit_hits(ptr, 0);
    return achdWithScratch(n, (p) => {
      achdWasm.module._achd_sim_limit_hits(ptr, 8 * p);
      return Array.from(achdWasm.module.HEAP32.subarray(2 * p, 2 * p + n), (i) => this._jointNames[i]);
    });
  }
  // Direction events since createSimulator() or reset() (copies), oldest first:
  // {t, step, link, direction, kind, sigma_min, unmet, effort_ratio} as in the CLI summary's "events"
  // ({t, step, loop, ...} for a loop joint's direction).
  events() {
    const ptr = this._live(), n = achdWasm.module._achd_sim_events(ptr, 0);
    const k = achdConstants();
    return achdWithScratch(9 * n, (p) => {
      achdWasm.module._achd_sim_events(ptr, 8 * p);
      const h = achdWasm.module.HEAPF64;
      return Array.from({ length: n }, (_, i) => {
        const e = p + 9 * i;
        const out = { t: h[e], step: h[e + 1] };
        if (h[e + 3] >= 0) out.loop = this._robot.loops[h[e + 3]].name;
        else out.link = this._linkNames[h[e + 2]];
        out.direction = k.directions[h[e + 4]];
        out.kind = k.direction_event_kinds[h[e + 5]];
        out.sigma_min = h[e + 6];
        out.unmet = h[e + 7];
        out.effort_ratio = h[e + 8];
        return out;
      });
    });
  }
  // How long (s) each direction of a link (omitted: the tip) was released since it was set.
  releasedSeconds(link) {
    const ptr = this._live(), l = this._linkIndex(link, 'releasedSeconds');
    const directions = achdConstants().directions;
    return achdWithScratch(directions.length, (p) => {
      if (achdWasm.module._achd_sim_released_seconds(ptr, l, 8 * p)) throw achdLastError();
      const out = {};
      directions.forEach((name, k) => { out[name] = achdWasm.module.HEAPF64[p + k]; });
      return out;
    });
  }
  // Events that happened but were not kept (beyond the simulator's capacity).
  get eventsNotKept() { return achdWasm.module._achd_sim_events_not_kept(this._live()); }
  // Outputs of the solve at the start of the last step (copies), named as the solver's.
  _result(name, n) {
    return achdCopy(achdWasm.module._achd_sim_result(this._live(), achdConstants().simulator_results.indexOf(name)), n);
  }
  nu() { return this._result('nu', achdWasm.module._achd_sim_nu_size(this._live())); }
  joint_torques() { return this._result('joint_torques', this.numRates); }
  qdd() { return this._result('qdd', this.numRates); }
  // per joint: a prescribed joint's torque (its trajectory's acceleration needs it), 0 for the others.
  prescribed_torques() { return this._result('prescribed_torques', this.numRates); }
  jointTorques() {
    achdDeprecated('Simulator.jointTorques()', 'Simulator.joint_torques()');
    return this.joint_torques();
  }
  // The wrench on one link (index after the root, or its name), base orientation.
  setExternalWrench(link, wrench) {
    this._live();
    const index = typeof link === 'string' ? this._linkNames.indexOf(link) : link;
    if (!Number.isInteger(index) || index < 0 || index >= this.numLinks)
      throw new Error(`setExternalWrench: unknown link ${achdShowRef(link)} (index 0..${this.numLinks - 1} or a link name)`);
    const w = achdReadNumbers(wrench, 'wrench', 6);
    this._ownView('f_ext').set(w, 6 * index);
  }
}
