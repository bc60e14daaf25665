// The end of the --post-js bundle (wasm/CMakeLists.txt): inside Emscripten's module
// factory, where the runtime's string helpers and its memory are in scope, bind the
// wrapper's modules to this module and install the API on it.
achdBind(Module, { UTF8ToString: UTF8ToString, stringToUTF8: stringToUTF8, lengthBytesUTF8: lengthBytesUTF8 },
  function achdDetachViews() {
    // WebAssembly.Memory.grow(0) adds no page but replaces the memory's ArrayBuffer,
    // detaching the old one: every typed array on it becomes zero-length (reads give
    // undefined, writes are dropped). Emscripten's HEAP* views are then made again on the
    // new buffer, as after growth.
    wasmMemory.grow(0);
    updateGlobalBufferAndViews(wasmMemory.buffer);
  });
installAchd(Module);
