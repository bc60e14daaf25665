// The end of the --post-js bundle (wasm/CMakeLists.txt): inside Emscripten's module
// factory, where the runtime's string helpers are in scope, bind the wrapper's modules to
// this module and install the API on it.
achdBind(Module, { UTF8ToString: UTF8ToString, stringToUTF8: stringToUTF8, lengthBytesUTF8: lengthBytesUTF8 });
installAchd(Module);
