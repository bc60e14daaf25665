// Copies out of wasm memory and scratch space in it.
import { achdWasm } from './runtime.mjs';

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
