// Checks of the values users pass (vectors, option objects, names), with the messages
// of the C++ side (tools/case_json.cpp), and the writes of checked vectors into wasm
// memory.
import { achdConstants, achdEffectBitsByKey } from './constants.mjs';
import { achdWasm } from './runtime.mjs';

export function achdIsArrayLike(v) {
  return Array.isArray(v) || (ArrayBuffer.isView(v) && !(v instanceof DataView));
}

// Checks n finite numbers, with the messages of tools/case_json.cpp: "q: expected 7
// values, got 6", "q[3] is not finite"; achdWriteVector then stores them into achdWasm.module.HEAPF64 at
// double index `at`.
export function achdCheckVector(value, field, n) {
  if (!achdIsArrayLike(value)) throw new Error(`${field} must be an array of ${n} numbers`);
  if (value.length !== n) throw new Error(`${field}: expected ${n} values, got ${value.length}`);
  for (let i = 0; i < n; ++i) {
    const x = value[i];
    if (typeof x !== 'number') throw new Error(`${field}[${i}] must be a number`);
    if (!Number.isFinite(x)) throw new Error(`${field}[${i}] is not finite`);
  }
}

export function achdWriteVector(value, field, n, at) {
  achdCheckVector(value, field, n);
  achdWasm.module.HEAPF64.set(value, at);
}

// A list of 6-vectors (alpha columns, f_ext wrenches) into achdWasm.module.HEAPF64 at double index `at`.
export function achdWriteSpatialList(value, field, count, at, what) {
  if (!Array.isArray(value)) throw new Error(`${field} must be an array of 6-element ${what}`);
  for (let k = 0; k < count; ++k) achdWriteVector(value[k], `${field}[${k}]`, 6, at + 6 * k);
}

export function achdCheckObject(value, name, known) {
  if (value === null || typeof value !== 'object' || Array.isArray(value))
    throw new Error(`${name} must be an object`);
  for (const key of Object.keys(value))
    if (!known.includes(key)) throw new Error(`${name}: unknown field '${key}'`);
}

// Effects: an object of booleans over `defaults`, or the raw achd::Effect bit mask.
export function achdEffectBits(effects, defaults, name) {
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

export function achdNonNegative(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value < 0)
    throw new Error(`${name} must be a finite number >= 0, got ${value}`);
  return value;
}

export function achdPositive(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0)
    throw new Error(`${name} must be a finite number > 0, got ${value}`);
  return value;
}

// The enum value of `value` (its index in the C++ name list `choices`); `fallback`, a
// name, when undefined.
export function achdChoice(value, choices, fallback, name) {
  const i = choices.indexOf(value === undefined ? fallback : value);
  if (i < 0) throw new Error(`${name}: expected ${choices.map((c) => `'${c}'`).join(' or ')}, got '${value}'`);
  return i;
}

export const ACHD_SOLVER_OPTION_KEYS = ['convention', 'policy', 'tolerance', 'absoluteTolerance', 'damping',
  'effects', 'frictionVelocity', 'maxConstraints'];

// Solver options (achd::Options, defaults from C++) -> the arguments of
// achd_solver_set_options. The bounds are achd::validate(Options)'s, checked here so that
// the message names the JS option.
export function achdSolverOptions(options) {
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
