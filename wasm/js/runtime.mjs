// The Emscripten module this wrapper drives, bound once by the module itself (glue.js,
// the end of the --post-js bundle that wasm/CMakeLists.txt builds from these files):
// achdWasm.module holds the wasm exports (`_achd_*`, `_malloc`, `_free`) and the heap
// views (`HEAPF64`, replaced when memory grows), achdWasm.text the string helpers that
// Emscripten keeps local. Every file of wasm/js reaches wasm only through this object,
// so each is an ES module that imports, lints and tests on its own.

export const achdWasm = { module: null, text: null };

// Called once by glue.js with the Emscripten module and its string helpers.
export function achdBind(module, text) {
  achdWasm.module = module;
  achdWasm.text = text;
}

export function achdLastError() {
  return new Error(achdWasm.text.UTF8ToString(achdWasm.module._achd_last_error()));
}

// The solver's sigma_min; a thrown Error when its K is beyond the range of a double.
export function achdSigmaMin(ptr) {
  const s = achdWasm.module._achd_solver_sigma_min(ptr);
  if (Number.isNaN(s)) throw achdLastError();
  return s;
}
