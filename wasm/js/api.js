// The JavaScript API of achd (--post-js: runs inside the Emscripten module factory, so
// it calls the wasm exports and reads HEAPF64 directly). `await createAchd()` resolves
// to the module with loadURDF() on it. Plain objects and arrays returned by the API are
// copies; the Float64Array properties of solvers and simulators are views on wasm
// memory, re-created automatically when memory grows. See wasm/achd.d.ts.

// What the wrapper mirrors from C++ (effect bits, enum names in enum order, defaults,
// the names of the buffers behind the views) is not copied here: achd_constants()
// (wasm/src/constants_api.cpp) returns it as JSON, read once on first use (the exports
// cannot be called before the runtime has started). No destructuring in this file:
// Emscripten 3.1.6's minifier drops destructured loop variables. Enum values cross the C ABI as their
// index in these name lists; JS option keys are the snake_case C++ names in camelCase.
let achdConstantsCache = null, achdEffectBitsCache = null;
function achdConstants() {
  if (achdConstantsCache === null) achdConstantsCache = achdDeepFreeze(JSON.parse(UTF8ToString(_achd_constants())));
  return achdConstantsCache;
}

// achd.Effects: the effect bits under their JS names ({gravity: 1, velocityProducts: 2, ...}).
function achdEffectBitsByKey() {
  if (achdEffectBitsCache === null)
    achdEffectBitsCache = Object.freeze(Object.fromEntries(
      Object.entries(achdConstants().effects).map((e) => [achdCamelCase(e[0]), e[1]])));
  return achdEffectBitsCache;
}

function achdCamelCase(name) {
  return name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());
}

function achdDeepFreeze(value) {
  if (value !== null && typeof value === 'object') {
    for (const v of Object.values(value)) achdDeepFreeze(v);
    Object.freeze(value);
  }
  return value;
}

// Spellings of the previous release, still accepted until the next one with a
// console.warn the first time each is used.
const ACHD_OLD_INTEGRATOR_NAMES = { euler: 'explicit_euler', 'semi-implicit': 'semi_implicit_euler' };
const achdWarned = new Set();
function achdDeprecated(what, instead) {
  if (achdWarned.has(what)) return;
  achdWarned.add(what);
  console.warn(`achd: ${what} is deprecated and will be removed in the next release; use ${instead}`);
}

// Simulator.step: steps per call into wasm (an int there), and between onProgress calls
// by default (about 0.1 s of the 7-DoF arm with RK4).
const ACHD_MAX_RUN_CHUNK = 2 ** 30;
const ACHD_PROGRESS_INTERVAL = 10000;

function achdLastError() {
  return new Error(UTF8ToString(_achd_last_error()));
}

// The solver's sigma_min; a thrown Error when its K is beyond the range of a double.
function achdSigmaMin(ptr) {
  const s = _achd_solver_sigma_min(ptr);
  if (Number.isNaN(s)) throw achdLastError();
  return s;
}

function achdIsArrayLike(v) {
  return Array.isArray(v) || (ArrayBuffer.isView(v) && !(v instanceof DataView));
}

// Checks n finite numbers, with the messages of tools/case_json.cpp: "q: expected 7
// values, got 6", "q[3] is not finite"; achdWriteVector then stores them into HEAPF64 at
// double index `at`.
function achdCheckVector(value, field, n) {
  if (!achdIsArrayLike(value)) throw new Error(`${field} must be an array of ${n} numbers`);
  if (value.length !== n) throw new Error(`${field}: expected ${n} values, got ${value.length}`);
  for (let i = 0; i < n; ++i) {
    const x = value[i];
    if (typeof x !== 'number') throw new Error(`${field}[${i}] must be a number`);
    if (!Number.isFinite(x)) throw new Error(`${field}[${i}] is not finite`);
  }
}

function achdWriteVector(value, field, n, at) {
  achdCheckVector(value, field, n);
  HEAPF64.set(value, at);
}

// A list of 6-vectors (alpha columns, f_ext wrenches) into HEAPF64 at double index `at`.
function achdWriteSpatialList(value, field, count, at, what) {
  if (!Array.isArray(value)) throw new Error(`${field} must be an array of 6-element ${what}`);
  for (let k = 0; k < count; ++k) achdWriteVector(value[k], `${field}[${k}]`, 6, at + 6 * k);
}

function achdCheckObject(value, name, known) {
  if (value === null || typeof value !== 'object' || Array.isArray(value))
    throw new Error(`${name} must be an object`);
  for (const key of Object.keys(value))
    if (!known.includes(key)) throw new Error(`${name}: unknown field '${key}'`);
}

// Effects: an object of booleans over `defaults`, or the raw achd::Effect bit mask.
function achdEffectBits(effects, defaults, name) {
  if (effects === undefined) return defaults;
  const all = achdConstants().all_effects, bits = achdEffectBitsByKey();
  if (typeof effects === 'number') {
    if (!Number.isInteger(effects) || effects < 0 || effects > all)
      throw new Error(`${name} must be an integer bit mask in [0, ${all}], got ${effects}`);
    return effects;
  }
  achdCheckObject(effects, name, Object.keys(bits));
  let mask = defaults;
  for (const key of Object.keys(effects)) {
    const on = effects[key];
    if (typeof on !== 'boolean') throw new Error(`${name}.${key} must be true or false`);
    mask = on ? mask | bits[key] : mask & ~bits[key];
  }
  return mask;
}

function achdNonNegative(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value < 0)
    throw new Error(`${name} must be a finite number >= 0, got ${value}`);
  return value;
}

function achdPositive(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0)
    throw new Error(`${name} must be a finite number > 0, got ${value}`);
  return value;
}

// The enum value of `value` (its index in the C++ name list `choices`); `fallback`, a
// name, when undefined.
function achdChoice(value, choices, fallback, name) {
  const i = choices.indexOf(value === undefined ? fallback : value);
  if (i < 0) throw new Error(`${name}: expected ${choices.map((c) => `'${c}'`).join(' or ')}, got '${value}'`);
  return i;
}

const ACHD_SOLVER_OPTION_KEYS = ['convention', 'policy', 'tolerance', 'absoluteTolerance', 'damping',
  'effects', 'frictionVelocity', 'maxConstraints'];

// Solver options (achd::Options, defaults from C++) -> the arguments of
// achd_solver_set_options. The bounds are achd::validate(Options)'s, checked here so that
// the message names the JS option.
function achdSolverOptions(options) {
  if (options === undefined || options === null) options = {};
  achdCheckObject(options, 'options', ACHD_SOLVER_OPTION_KEYS);
  if (options.absoluteTolerance !== undefined && typeof options.absoluteTolerance !== 'boolean')
    throw new Error('options.absoluteTolerance must be true or false');
  const k = achdConstants(), d = k.options;
  return [
    achdChoice(options.convention, k.conventions, d.convention, 'options.convention'),
    achdChoice(options.policy, k.singularity_policies, d.policy, 'options.policy'),
    achdNonNegative(options.tolerance, d.tolerance, 'options.tolerance'),
    (options.absoluteTolerance === undefined ? d.absolute_tolerance : options.absoluteTolerance) ? 1 : 0,
    achdPositive(options.damping, d.damping, 'options.damping'),
    achdEffectBits(options.effects, d.effects, 'options.effects'),
    achdPositive(options.frictionVelocity, d.friction_velocity, 'options.frictionVelocity'),
  ];
}

// Copies `n` doubles starting at byte address `ptr` into a plain array.
function achdCopy(ptr, n) {
  return Array.from(HEAPF64.subarray(ptr >> 3, (ptr >> 3) + n));
}

function achdChunks(flat, size) {
  const out = [];
  for (let i = 0; i < flat.length; i += size) out.push(flat.slice(i, i + size));
  return out;
}

// Runs fn(p) with p the double index of `n` scratch doubles in wasm memory.
function achdWithScratch(n, fn) {
  const bytes = _malloc(8 * Math.max(n, 1));
  try {
    return fn(bytes >> 3);
  } finally {
    _free(bytes);
  }
}

function achdWithString(text, fn) {
  const size = lengthBytesUTF8(text) + 1;
  const p = _malloc(size);
  try {
    stringToUTF8(text, p, size);
    return fn(p);
  } finally {
    _free(p);
  }
}

// The part every wasm-owning object shares: a pointer, delete(), and Float64Array views
// re-created whenever the wasm memory buffer has been replaced by growth.
class AchdHandle {
  constructor(kind, ptr, free) {
    this._kind = kind;
    this._ptr = ptr;
    this._free = free;
    this._buffer = null;
    this._views = null;
  }
  _live() {
    if (this._ptr === 0) throw new Error(`${this._kind} has been deleted`);
    return this._ptr;
  }
  // _layout(): [name, length] per view; _bufferNames(): the C++ buffer names (index =
  // the buffer's number in achd_*_buffer); _bufferOf(ptr, index): its byte address.
  _view(name) {
    if (this._ptr === 0) throw new Error(`${this._kind} has been deleted`);
    if (this._buffer !== HEAPF64.buffer) this._mapViews();
    return this._views[name];
  }
  _mapViews() {
    this._buffer = HEAPF64.buffer;
    this._views = {};
    const names = this._bufferNames();
    for (const v of this._layout())  // v = [name, length]
      this._views[v[0]] = new Float64Array(this._buffer, this._bufferOf(this._ptr, names.indexOf(v[0])), v[1]);
  }
  get deleted() { return this._ptr === 0; }
  delete() {
    this._live();
    this._free(this._ptr);
    this._ptr = 0;
    this._views = null;
    this._buffer = null;
  }
}

// The zero-copy solver: write the views, call solve(), read the views.
class Solver extends AchdHandle {
  constructor(robot, ptr, maxConstraints) {
    super('Solver', ptr, _achd_solver_delete);
    this.numJoints = robot.numJoints;
    this.numLinks = robot.numLinks;
    this.maxConstraints = maxConstraints;
    this._nc = 0;
    this._external = false;
  }
  _bufferOf(ptr, index) { return _achd_solver_buffer(ptr, index); }
  _bufferNames() { return achdConstants().solver_buffers; }
  _layout() {
    const nj = this.numJoints, nl = this.numLinks, mc = this.maxConstraints;
    return [['q', nj], ['qd', nj], ['ff_torques', nj], ['gravity', 3], ['alpha', 6 * mc], ['beta', mc],
      ['f_ext', 6 * nl], ['qdd', nj], ['nu', this._nc], ['joint_torques', nj], ['constraint_torques', nj],
      ['total_torques', nj], ['link_accelerations', 6 * (nl + 1)], ['constraint_wrench', 6]];
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
  get rank() { return _achd_solver_rank(this._live()); }
  get sigma_min() { return achdSigmaMin(this._live()); }
  get numConstraints() { this._live(); return this._nc; }
  set numConstraints(nc) {
    if (!Number.isInteger(nc)) throw new Error(`numConstraints must be an integer, got ${nc}`);
    if (_achd_solver_set_num_constraints(this._live(), nc)) throw achdLastError();
    this._nc = nc;
    this._buffer = null;  // the nu view's length changed
  }
  get useExternalWrenches() { this._live(); return this._external; }
  set useExternalWrenches(on) {
    if (typeof on !== 'boolean') throw new Error('useExternalWrenches must be true or false');
    _achd_solver_use_external_wrenches(this._live(), on ? 1 : 0);
    this._external = on;
  }
  setOptions(options) {
    const ptr = this._live();
    _achd_solver_set_options(ptr, ...achdSolverOptions(options));
  }
  // hybrid_dynamics on the views, in place: no allocation, no copy.
  solve() {
    if (_achd_solver_solve(this._ptr === 0 ? this._live() : this._ptr)) throw achdLastError();
  }
  // The outputs of the last solve as plain arrays (the result object of docs/design.md
  // section 5; a copy).
  result() {
    const ptr = this._live();
    const nj = this.numJoints, nc = _achd_solver_nu_size(ptr);
    const rows = _achd_solver_dropped_rows(ptr), cols = _achd_solver_dropped_cols(ptr);
    const names = this._bufferNames();
    const copy = (name, n) => achdCopy(_achd_solver_buffer(ptr, names.indexOf(name)), n);
    return {
      qdd: copy('qdd', nj),
      constraint_torques: copy('constraint_torques', nj),
      total_torques: copy('total_torques', nj),
      nu: copy('nu', nc),
      joint_torques: copy('joint_torques', nj),
      constraint_wrench: copy('constraint_wrench', 6),
      link_accelerations: achdChunks(copy('link_accelerations', 6 * (this.numLinks + 1)), 6),
      rank: _achd_solver_rank(ptr),
      sigma_min: achdSigmaMin(ptr),
      dropped: rows ? achdChunks(copy('dropped', rows * cols), rows) : [],
    };
  }
}

// Time stepping; q, qd, ff_torques, f_ext are views on the simulator's state.
class Simulator extends AchdHandle {
  constructor(robot, ptr) {
    super('Simulator', ptr, _achd_sim_delete);
    this.numJoints = robot.numJoints;
    this.numLinks = robot.numLinks;
    this._linkNames = robot.linkNames;
    this._jointNames = robot.jointNames;
  }
  _bufferOf(ptr, index) { return _achd_sim_buffer(ptr, index); }
  _bufferNames() { return achdConstants().simulator_buffers; }
  _layout() {
    return [['q', this.numJoints], ['qd', this.numJoints], ['t', 1], ['ff_torques', this.numJoints],
      ['f_ext', 6 * this.numLinks]];
  }
  get q() { return this._view('q'); }
  get qd() { return this._view('qd'); }
  get ff_torques() { return this._view('ff_torques'); }
  get f_ext() { return this._view('f_ext'); }
  get t() { return this._view('t')[0]; }
  // n steps of dt (n up to 2^53 - 1), given to wasm in chunks (its run() takes an int);
  // with options.onProgress, chunks of options.progressInterval steps, after each of
  // which onProgress(stepsDone, n) is called: returning false stops the run. Returns the
  // number of steps run. A failed step throws (the state stays at the last good step).
  step(n = 1, dt = 1e-3, options = undefined) {
    const ptr = this._live();
    if (!Number.isSafeInteger(n) || n < 0)
      throw new Error(`step: n must be an integer >= 0 and <= 2^53 - 1, got ${n}`);
    if (typeof dt !== 'number' || !Number.isFinite(dt) || dt <= 0)
      throw new Error(`step: dt must be a finite number > 0, got ${dt}`);
    if (options === undefined || options === null) options = {};
    achdCheckObject(options, 'step options', ['onProgress', 'progressInterval']);
    const onProgress = options.onProgress;
    if (onProgress !== undefined && typeof onProgress !== 'function')
      throw new Error('step options.onProgress must be a function (stepsDone, total) => boolean');
    const interval = options.progressInterval === undefined ? ACHD_PROGRESS_INTERVAL : options.progressInterval;
    if (!Number.isSafeInteger(interval) || interval < 1)
      throw new Error(`step options.progressInterval must be an integer >= 1, got ${interval}`);
    const chunk = Math.min(onProgress ? interval : ACHD_MAX_RUN_CHUNK, ACHD_MAX_RUN_CHUNK);
    let done = 0;
    while (done < n) {
      const k = Math.min(chunk, n - done);
      if (_achd_sim_run(ptr, k, dt)) throw achdLastError();
      done += k;
      if (onProgress && onProgress(done, n) === false) break;
    }
    return done;
  }
  // Steps completed since createSimulator() or reset().
  get stepsTaken() { return _achd_sim_steps_taken(this._live()); }
  reset(q, qd) {
    const ptr = this._live(), n = this.numJoints;
    achdWithScratch(2 * n, (p) => {
      achdWriteVector(q, 'q', n, p);
      if (qd === undefined) HEAPF64.fill(0, p + n, p + 2 * n);
      else achdWriteVector(qd, 'qd', n, p + n);
      if (_achd_sim_reset(ptr, 8 * p, 8 * (p + n))) throw achdLastError();
    });
    this._buffer = null;  // reset() may have given q and qd new buffers
  }
  // name: x y z rx ry rz; mode: 'hold', 'free' or a number (classical acceleration setpoint).
  setDirection(name, mode) {
    const ptr = this._live();
    const directions = achdConstants().directions, modes = achdConstants().direction_modes;
    const index = directions.indexOf(name);
    if (index < 0) throw new Error(`setDirection: unknown direction '${name}' (${directions.join(', ')})`);
    let code, setpoint = 0;
    if (mode === 'free' || mode === 'hold') code = modes.indexOf(mode);
    else if (typeof mode === 'number' && Number.isFinite(mode)) { code = modes.indexOf('accelerate'); setpoint = mode; }
    else throw new Error(`setDirection: mode must be 'hold', 'free' or a finite number, got ${mode}`);
    if (_achd_sim_set_direction(ptr, index, code, setpoint)) throw achdLastError();
  }
  // Held-direction residuals (m or rad); null for directions that are not held (free
  // or accelerated: neither has a position or angle to keep).
  residuals() {
    const ptr = this._live();
    const directions = achdConstants().directions, modes = achdConstants().direction_modes;
    return achdWithScratch(directions.length, (p) => {
      _achd_sim_residuals(ptr, 8 * p);
      const out = {};
      directions.forEach((name, k) => {
        out[name] = _achd_sim_direction_mode(ptr, k) === modes.indexOf('hold') ? HEAPF64[p + k] : null;
      });
      return out;
    });
  }
  energy() {
    const ptr = this._live();
    const kinetic = _achd_sim_kinetic_energy(ptr), potential = _achd_sim_potential_energy(ptr);
    return { kinetic, potential, total: kinetic + potential };
  }
  // Names of the joints at or past a limit after the last step (a copy; [] under 'ignore').
  limitHits() {
    const ptr = this._live(), n = _achd_sim_limit_hits(ptr, 0);
    return achdWithScratch(n, (p) => {
      _achd_sim_limit_hits(ptr, 8 * p);
      return Array.from(HEAP32.subarray(2 * p, 2 * p + n), (i) => this._jointNames[i]);
    });
  }
  // Outputs of the solve at the start of the last step (copies), named as the solver's.
  _result(name, n) {
    return achdCopy(_achd_sim_result(this._live(), achdConstants().simulator_results.indexOf(name)), n);
  }
  nu() { return this._result('nu', _achd_sim_nu_size(this._live())); }
  joint_torques() { return this._result('joint_torques', this.numJoints); }
  qdd() { return this._result('qdd', this.numJoints); }
  jointTorques() {
    achdDeprecated('Simulator.jointTorques()', 'Simulator.joint_torques()');
    return this.joint_torques();
  }
  // The wrench on one link (index after the root, or its name), base orientation.
  setExternalWrench(link, wrench) {
    this._live();
    const index = typeof link === 'string' ? this._linkNames.indexOf(link) : link;
    if (!Number.isInteger(index) || index < 0 || index >= this.numLinks)
      throw new Error(`setExternalWrench: unknown link ${JSON.stringify(link)} (index 0..${this.numLinks - 1} or a link name)`);
    achdCheckVector(wrench, 'wrench', 6);
    this.f_ext.set(wrench, 6 * index);
  }
}

class Robot extends AchdHandle {
  constructor(ptr) {
    super('Robot', ptr, _achd_robot_delete);
    const info = JSON.parse(UTF8ToString(_achd_robot_info(ptr)));
    const bound = (x) => (Math.abs(x) >= 1e300 ? Math.sign(x) * Infinity : x);
    this.root = info.root;
    this.tip = info.tip;
    this.numJoints = info.joints.length;
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
    const s = _achd_solver_create(ptr, mc);
    if (!s) throw achdLastError();
    _achd_solver_set_options(s, ...args);
    return new Solver(this, s, mc);  // gravity: the C++ Case's default
  }
  // The case object in, the result object out (docs/design.md section 5; plain arrays:
  // copies).
  solve(c, options) {
    this._live();
    achdCheckObject(c, 'the case', ['q', 'qd', 'gravity', 'alpha', 'beta', 'f_ext', 'ff_torques']);
    if (!('q' in c)) throw new Error("missing required field 'q'");
    if (!('gravity' in c)) throw new Error("missing required field 'gravity'");
    const args = achdSolverOptions(options);
    if (!this._solver) this._solver = this.createSolver();
    const s = this._solver, ptr = s._ptr, nj = this.numJoints, nl = this.numLinks;
    const names = s._bufferNames(), max = achdConstants().max_constraints;
    const at = (name) => _achd_solver_buffer(ptr, names.indexOf(name)) >> 3;
    achdWriteVector(c.q, 'q', nj, at('q'));
    achdWriteVector(c.gravity, 'gravity', 3, at('gravity'));
    if (c.qd === undefined) HEAPF64.fill(0, at('qd'), at('qd') + nj);
    else achdWriteVector(c.qd, 'qd', nj, at('qd'));
    if (c.ff_torques === undefined) HEAPF64.fill(0, at('ff_torques'), at('ff_torques') + nj);
    else achdWriteVector(c.ff_torques, 'ff_torques', nj, at('ff_torques'));
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
      HEAPF64.fill(0, at('beta'), at('beta') + nc);
    }
    if (c.f_ext !== undefined) {
      if (!Array.isArray(c.f_ext)) throw new Error('f_ext must be an array of 6-element wrenches');
      if (c.f_ext.length !== nl)
        throw new Error(`f_ext: expected ${nl} wrenches (one per link after the root), got ${c.f_ext.length}`);
      s.useExternalWrenches = true;
      achdWriteSpatialList(c.f_ext, 'f_ext', nl, at('f_ext'), 'wrenches');
    } else {
      s.useExternalWrenches = false;
    }
    s.numConstraints = nc;
    _achd_solver_set_options(ptr, ...args);
    s.solve();
    return s.result();
  }
  _q(q, p) { achdWriteVector(q, 'q', this.numJoints, p); }
  // [{name, position: [x, y, z], rotation: [9, row-major]}] per link after the root.
  forwardKinematics(q) {
    const ptr = this._live(), nj = this.numJoints, nl = this.numLinks;
    return achdWithScratch(nj + 12 * nl, (p) => {
      this._q(q, p);
      if (_achd_robot_forward_kinematics(ptr, 8 * p, 8 * (p + nj))) throw achdLastError();
      return this.linkNames.map((name, l) => {
        const o = p + nj + 12 * l;
        return { name, position: Array.from(HEAPF64.subarray(o, o + 3)),
          rotation: Array.from(HEAPF64.subarray(o + 3, o + 12)) };
      });
    });
  }
  // 6 rows (linear first) of nj numbers: [v; w] of the tip link's origin = J qd.
  tipJacobian(q) {
    const ptr = this._live(), nj = this.numJoints;
    return achdWithScratch(7 * nj, (p) => {
      this._q(q, p);
      if (_achd_robot_tip_jacobian(ptr, 8 * p, 8 * (p + nj))) throw achdLastError();
      return achdChunks(Array.from(HEAPF64.subarray(p + nj, p + 7 * nj)), nj);
    });
  }
  // M(q) as nj rows, rotor inertia included unless {rotorInertia: false}.
  massMatrix(q, options) {
    const ptr = this._live(), nj = this.numJoints;
    if (options === undefined) options = {};
    achdCheckObject(options, 'options', ['rotorInertia']);
    const rotor = options.rotorInertia === undefined ? true : options.rotorInertia;
    if (typeof rotor !== 'boolean') throw new Error('options.rotorInertia must be true or false');
    return achdWithScratch(nj + nj * nj, (p) => {
      this._q(q, p);
      if (_achd_robot_mass_matrix(ptr, 8 * p, rotor ? 1 : 0, 8 * (p + nj))) throw achdLastError();
      return achdChunks(Array.from(HEAPF64.subarray(p + nj, p + nj + nj * nj)), Math.max(nj, 1));
    });
  }
  // Inverse dynamics: the joint torques for (q, qd, qdd) under gravity and f_ext.
  rnea(q, qd, qdd, options) {
    const ptr = this._live(), nj = this.numJoints, nl = this.numLinks;
    if (options === undefined) options = {};
    achdCheckObject(options, 'options', ['gravity', 'f_ext', 'effects', 'frictionVelocity']);
    const k = achdConstants();
    const effects = achdEffectBits(options.effects, k.options.effects, 'options.effects');
    const fv = achdPositive(options.frictionVelocity, k.options.friction_velocity, 'options.frictionVelocity');
    return achdWithScratch(4 * nj + 3 + 6 * nl, (p) => {
      const g = p + 4 * nj, f = g + 3;
      this._q(q, p);
      achdWriteVector(qd, 'qd', nj, p + nj);
      achdWriteVector(qdd, 'qdd', nj, p + 2 * nj);
      achdWriteVector(options.gravity === undefined ? k.case_gravity : options.gravity, 'gravity', 3, g);
      if (options.f_ext !== undefined) {
        if (!Array.isArray(options.f_ext) || options.f_ext.length !== nl)
          throw new Error(`f_ext: expected ${nl} wrenches (one per link after the root), got ${
            Array.isArray(options.f_ext) ? options.f_ext.length : typeof options.f_ext}`);
        achdWriteSpatialList(options.f_ext, 'f_ext', nl, f, 'wrenches');
      }
      if (_achd_robot_rnea(ptr, 8 * p, 8 * (p + nj), 8 * (p + 2 * nj), 8 * g,
        options.f_ext === undefined ? 0 : 8 * f, effects, fv, 8 * (p + 3 * nj))) throw achdLastError();
      return Array.from(HEAPF64.subarray(p + 3 * nj, p + 4 * nj));
    });
  }
  createSimulator(options) {
    const ptr = this._live();
    if (options === undefined || options === null) options = {};
    achdCheckObject(options, 'options', ['integrator', 'effects', 'gravity', 'limits',
      'frictionVelocity', 'stabilisationFrequency', 'stabilisationDamping']);
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
    const frequency = achdNonNegative(options.stabilisationFrequency, d.stabilisation_frequency, 'options.stabilisationFrequency');
    const damping = achdPositive(options.stabilisationDamping, d.stabilisation_damping, 'options.stabilisationDamping');
    const create = (gravity) => _achd_sim_create(ptr, integrator, effects, gravity, limits, frictionVelocity,
      frequency, damping);
    const sim = options.gravity === undefined ? create(0) : achdWithScratch(3, (p) => {
      achdWriteVector(options.gravity, 'gravity', 3, p);
      return create(8 * p);
    });
    if (!sim) throw achdLastError();
    return new Simulator(this, sim);
  }
}

// Loads the chain root -> tip from URDF text; throws an Error naming the problem.
// options.mimic: 'error' (default: a <mimic> joint on the chain is an error) or
// 'independent' (loaded as a joint of its own, as KDL does); achd::MimicJoints' order.
Module['loadURDF'] = function loadURDF(text, options) {
  if (typeof text !== 'string') throw new Error('loadURDF: the URDF must be a string');
  achdCheckObject(options, 'loadURDF options', ['root', 'tip', 'mimic']);
  for (const key of ['root', 'tip'])
    if (typeof options[key] !== 'string') throw new Error(`loadURDF: options.${key} must be a link name`);
  const mimic = achdChoice(options.mimic, ['error', 'independent'], 'error', 'loadURDF: options.mimic');
  const ptr = achdWithString(text, (x) => achdWithString(options.root, (r) =>
    achdWithString(options.tip, (t) => _achd_robot_load(x, r, t, mimic))));
  if (!ptr) throw achdLastError();
  return new Robot(ptr);
};
// Bytes of wasm memory (grows, never shrinks): for leak checks.
Module['memoryBytes'] = function memoryBytes() { return HEAPU8.length; };
// achd.Effects: the effect bits by JS name; achd.constants: everything achd_constants()
// describes (both frozen, from C++).
Object.defineProperty(Module, 'Effects', { enumerable: true, get: achdEffectBitsByKey });
Object.defineProperty(Module, 'constants', { enumerable: true, get: () => achdConstants() });
