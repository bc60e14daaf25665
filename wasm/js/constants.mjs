// What the wrapper mirrors from C++ (effect bits, enum names in enum order, defaults,
// the names of the buffers behind the views) is not copied here: achd_constants()
// (wasm/src/constants_api.cpp) returns it as JSON, read once on first use (the exports
// cannot be called before the runtime has started). Enum values cross the C ABI as their
// index in these name lists; JS option keys are the snake_case C++ names in camelCase.
// Also the previous release's spellings, accepted with a deprecation warning.
import { achdWasm } from './runtime.mjs';

let achdConstantsCache = null, achdEffectBitsCache = null;
export function achdConstants() {
  if (achdConstantsCache === null) achdConstantsCache = achdDeepFreeze(JSON.parse(achdWasm.text.UTF8ToString(achdWasm.module._achd_constants())));
  return achdConstantsCache;
}

// achd.Effects: the effect bits under their JS names ({gravity: 1, velocityProducts: 2, ...}).
export function achdEffectBitsByKey() {
  if (achdEffectBitsCache === null)
    achdEffectBitsCache = Object.freeze(Object.fromEntries(
      Object.entries(achdConstants().effects).map((e) => [achdCamelCase(e[0]), e[1]])));
  return achdEffectBitsCache;
}

export function achdCamelCase(name) {
  return name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());
}

export function achdDeepFreeze(value) {
  if (value !== null && typeof value === 'object') {
    for (const v of Object.values(value)) achdDeepFreeze(v);
    Object.freeze(value);
  }
  return value;
}

// Spellings of the previous release, still accepted until the next one with a
// console.warn the first time each is used.
export const ACHD_OLD_INTEGRATOR_NAMES = { euler: 'explicit_euler', 'semi-implicit': 'semi_implicit_euler' };
export const achdWarned = new Set();
export function achdDeprecated(what, instead) {
  if (achdWarned.has(what)) return;
  achdWarned.add(what);
  console.warn(`achd: ${what} is deprecated and will be removed in the next release; use ${instead}`);
}

// Simulator.step: steps per call into wasm (an int there), and between onProgress calls
