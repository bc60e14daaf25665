// The Emscripten module this wrapper drives, bound once by the module itself (glue.js,
// the end of the --post-js bundle that wasm/CMakeLists.txt builds from these files):
// achdWasm.module holds the wasm exports (`_achd_*`, `_malloc`, `_free`) and the heap
// views (`HEAPF64`, replaced when memory grows), achdWasm.text the string helpers that
// Emscripten keeps local, achdWasm.detachViews() makes every Float64Array on the current
// wasm memory zero-length (handle.mjs calls it when an object whose views were handed out
// is deleted). Every file of wasm/js reaches wasm only through this object, so each is
// an ES module that imports, lints and tests on its own.

export const achdWasm = { module: null, text: null, detachViews: null };

// Called once by glue.js with the Emscripten module, its string helpers and the detach.
export function achdBind(module, text, detachViews) {
  achdWasm.module = module;
  achdWasm.text = text;
  achdWasm.detachViews = detachViews;
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
