// Checks of the values users pass to the API's own calls (option objects, the
// simulator's vectors, names); a case and its fields are C++'s (json_text.mjs), with the
// CLI's messages, which those of the vectors here follow.
//
// Every input is read once: an array's length and each element are read one time into a
// copy (a typed array's elements straight from its memory), an object's own properties
// one time into a null-prototype copy, and the checks and the writes into wasm memory
// use only that copy. A getter on an element or a property is refused (its value could
// differ between reads, and it runs the caller's code in the middle of a call), so is an
// object that is not an array, a typed array or a plain {name: value} object (a Map, a
// DataView, a class instance). A Proxy is read through its own-property traps once, so
// what it gives on a second read never matters. Callers read all of their inputs before
// they take the object's pointer: code run by a read (a Proxy's trap) that deletes the
// object is then caught by _live().
import { achdConstants, achdEffectBitsByKey } from './constants.mjs';

// Arrays longer than this are refused before their elements are read (no input of the
// API comes near: the largest, f_ext of a 10,000-link tree, has 60,000 numbers).
export const ACHD_MAX_INPUT_LENGTH = 1 << 24;

export const ACHD_TYPED_ARRAYS = [Float64Array, Float32Array, Int32Array, Uint32Array, Int16Array, Uint16Array,
  Int8Array, Uint8Array, Uint8ClampedArray];

// An object literal or Object.create(null): what name-keyed inputs and options must be.
export function achdIsPlainObject(v) {
  if (v === null || typeof v !== 'object' || Array.isArray(v) || ArrayBuffer.isView(v)) return false;
  const proto = Object.getPrototypeOf(v);
  return proto === Object.prototype || proto === null;
}

// A value for a message: numbers as given (2**31 is 2147483648, not an int32), strings
// quoted, other things by their kind (calls no toString of the caller's).
export function achdDescribe(x) {
  switch (typeof x) {
    case 'number': case 'boolean': return String(x);
    case 'bigint': return `${String(x)}n (a BigInt)`;
    case 'string': return `'${x}'`;
    case 'undefined': return 'undefined';
    case 'symbol': return 'a symbol';
    case 'function': return 'a function';
    default: break;
  }
  if (x === null) return 'null';
  if (Array.isArray(x)) return 'an array';
  if (x instanceof DataView) return 'a DataView';
  if (ArrayBuffer.isView(x)) {
    const type = ACHD_TYPED_ARRAYS.find((T) => x instanceof T);
    return type ? `a ${type.name}` : 'a BigInt typed array';
  }
  if (x instanceof ArrayBuffer) return 'an ArrayBuffer';
  if (x instanceof Map) return 'a Map';
  if (x instanceof Set) return 'a Set';
  return achdIsPlainObject(x) ? 'an object' : 'a class instance (not a plain object)';
}

// ", got a Map" for the kinds of values JSON cannot hold (Map, DataView, class instance,
// symbol...), nothing for the others: for those the message is the CLI's word for word.
export function achdUnlikeJson(x) {
  if (x === null || x === undefined || Array.isArray(x) || achdIsPlainObject(x)) return '';
  if (typeof x === 'string' || typeof x === 'number' || typeof x === 'boolean') return '';
  return `, got ${achdDescribe(x)}`;
}

// An array input read once (see the top): a plain Array of its elements as given, or for
// a typed array a Float64Array copy. `expected` completes "FIELD must be ...";
// checkLength(length) throws when the length is wrong, before any element is read.
export function achdReadArray(value, field, expected, checkLength) {
  if (ArrayBuffer.isView(value) && !(value instanceof DataView)) {
    if (!ACHD_TYPED_ARRAYS.some((T) => value instanceof T))
      throw new Error(`${field} must be ${expected}${achdUnlikeJson(value)}`);
    if (checkLength) checkLength(value.length);
    return new Float64Array(value);  // the typed array's own elements, not its properties
  }
  if (!Array.isArray(value)) throw new Error(`${field} must be ${expected}${achdUnlikeJson(value)}`);
  const lengthProperty = Object.getOwnPropertyDescriptor(value, 'length');
  const n = lengthProperty === undefined ? undefined : lengthProperty.value;
  if (!Number.isSafeInteger(n) || n < 0) throw new Error(`${field} must be ${expected}, got an array of length ${achdDescribe(n)}`);
  if (checkLength) checkLength(n);
  if (n > ACHD_MAX_INPUT_LENGTH) throw new Error(`${field}: ${n} values, more than the ${ACHD_MAX_INPUT_LENGTH} an input may have`);
  const out = new Array(n);
  for (let i = 0; i < n; ++i) {
    const d = Object.getOwnPropertyDescriptor(value, i);
    if (d !== undefined && !('value' in d)) throw new Error(`${field}[${i}] is a getter: give plain values`);
    out[i] = d === undefined ? undefined : d.value;
  }
  return out;
}

export function achdFiniteNumber(x, where) {
  if (typeof x !== 'number') throw new Error(`${where} must be a number${achdUnlikeJson(x)}`);
  if (!Number.isFinite(x)) throw new Error(`${where} is not finite`);
  return x;
}

// n finite numbers read once into a Float64Array, with the messages of tools/case_json.cpp:
// "q: expected 7 values, got 6", "q[3] is not finite". `count` words the expected count
// in the length message (default "N values"), `expected` what the input must be.
export function achdReadNumbers(value, field, n, count = `${n} values`, expected = `an array of ${n} numbers`) {
  const a = achdReadArray(value, field, expected, (length) => {
    if (length !== n) throw new Error(`${field}: expected ${count}, got ${length}`);
  });
  const out = new Float64Array(n);
  for (let i = 0; i < n; ++i) out[i] = achdFiniteNumber(a[i], `${field}[${i}]`);
  return out;
}

// An options or name-keyed object read once into a null-prototype copy of its own
// enumerable properties (so a key '__proto__' is a key like any other). It must be a
// plain object; a key not in `known` (null: any key) or a getter is an error.
export function achdCheckObject(value, name, known) {
  if (!achdIsPlainObject(value)) throw new Error(`${name} must be an object${achdUnlikeJson(value)}`);
  const out = Object.create(null);
  for (const key of Reflect.ownKeys(value)) {
    if (typeof key !== 'string') continue;  // symbol keys name nothing
    const d = Object.getOwnPropertyDescriptor(value, key);
    if (d === undefined || !d.enumerable) continue;
    if (known !== null && !known.includes(key)) throw new Error(`${name}: unknown field '${key}'`);
    if (!('value' in d)) throw new Error(`${name}.${key} is a getter: give plain values`);
    out[key] = d.value;
  }
  return out;
}

// Options that may be omitted (undefined: no options); null and anything but a plain
// object are named errors. Returns the copy as achdCheckObject.
export function achdOptionalObject(value, name, known) {
  return value === undefined ? Object.create(null) : achdCheckObject(value, name, known);
}

// Effects: an object of booleans over `defaults`, or the raw achd::Effect bit mask.
export function achdEffectBits(effects, defaults, name) {
  if (effects === undefined) return defaults;
  const all = achdConstants().all_effects, bits = achdEffectBitsByKey();
  if (typeof effects === 'number') {
    if (!Number.isInteger(effects) || effects < 0 || effects > all)
      throw new Error(`${name} must be an integer bit mask in [0, ${all}], got ${achdDescribe(effects)}`);
    return effects;
  }
  const given = achdCheckObject(effects, name, Object.keys(bits));
  let mask = defaults;
  for (const key of Object.keys(given)) {
    const on = given[key];
    if (typeof on !== 'boolean') throw new Error(`${name}.${key} must be true or false`);
    mask = on ? mask | bits[key] : mask & ~bits[key];
  }
  return mask;
}

export function achdNonNegative(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value < 0)
    throw new Error(`${name} must be a finite number >= 0, got ${achdDescribe(value)}`);
  return value;
}

export function achdPositive(value, fallback, name) {
  if (value === undefined) return fallback;
  if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0)
    throw new Error(`${name} must be a finite number > 0, got ${achdDescribe(value)}`);
  return value;
}

// The enum value of `value` (its index in the C++ name list `choices`); `fallback`, a
// name, when undefined.
export function achdChoice(value, choices, fallback, name) {
  const i = choices.indexOf(value === undefined ? fallback : value);
  if (i < 0) throw new Error(`${name}: expected ${choices.map((c) => `'${c}'`).join(' or ')}, got ${achdDescribe(value)}`);
  return i;
}

export const ACHD_SOLVER_OPTION_KEYS = ['convention', 'policy', 'tolerance', 'absoluteTolerance', 'damping',
  'effects', 'frictionVelocity', 'maxConstraints'];

// Solver options (achd::Options, defaults from C++) -> the arguments of
// achd_solver_set_options. The bounds are achd::validate(Options)'s, checked here so that
// the message names the JS option.
export function achdSolverOptions(options) {
  if (options === undefined) options = {};  // (null: a named error)
  const o = achdCheckObject(options, 'options', ACHD_SOLVER_OPTION_KEYS);
  if (o.absoluteTolerance !== undefined && typeof o.absoluteTolerance !== 'boolean')
    throw new Error('options.absoluteTolerance must be true or false');
  const k = achdConstants(), d = k.options;
  return [
    achdChoice(o.convention, k.conventions, d.convention, 'options.convention'),
    achdChoice(o.policy, k.singularity_policies, d.policy, 'options.policy'),
    achdNonNegative(o.tolerance, d.tolerance, 'options.tolerance'),
    (o.absoluteTolerance === undefined ? d.absolute_tolerance : o.absoluteTolerance) ? 1 : 0,
    achdPositive(o.damping, d.damping, 'options.damping'),
    achdEffectBits(o.effects, d.effects, 'options.effects'),
    achdPositive(o.frictionVelocity, d.friction_velocity, 'options.frictionVelocity'),
  ];
}
