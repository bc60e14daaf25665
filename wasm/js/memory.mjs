// Copies out of wasm memory and scratch space in it.
import { achdLastError, achdWasm } from './runtime.mjs';

// Copies `n` doubles starting at byte address `ptr` into a plain array.
export function achdCopy(ptr, n) {
  return Array.from(achdWasm.module.HEAPF64.subarray(ptr >> 3, (ptr >> 3) + n));
}

export function achdChunks(flat, size) {
  const out = [];
  for (let i = 0; i < flat.length; i += size) out.push(flat.slice(i, i + size));
  return out;
}

// Runs fn(p) with p the double index of `n` scratch doubles in wasm memory.
export function achdWithScratch(n, fn) {
  const bytes = achdWasm.module._malloc(8 * Math.max(n, 1));
  try {
    return fn(bytes >> 3);
  } finally {
    achdWasm.module._free(bytes);
  }
}

export function achdWithString(text, fn) {
  const size = achdWasm.text.lengthBytesUTF8(text) + 1;
  const p = achdWasm.module._malloc(size);
  try {
    achdWasm.text.stringToUTF8(text, p, size);
    return fn(p);
  } finally {
    achdWasm.module._free(p);
  }
}

// The result object of a solve from the C++ result JSON at byte address `ptr` (null: the
// call failed, its reason in achd_last_error()). C++ writes 17 significant digits: each
// number reads back as the double it was.
export function achdResultOf(ptr) {
  if (!ptr) throw achdLastError();
  const text = achdWasm.text.UTF8ToString(ptr);
  try {
    return JSON.parse(text);
  } catch (e) {  // (a number JSON cannot hold: the solve checks for those)
    throw new Error(`the result is not JSON: ${e.message}`);
  }
}
