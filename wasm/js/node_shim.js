// Runs before the Emscripten output (--extern-pre-js). Emscripten 3.1.6's ES module
// build still calls require() and reads __dirname/__filename under Node, which ES
// modules lack: define them from the module's own URL. Browsers skip this block.
const achdIsNode = typeof process === 'object' && typeof process.versions === 'object' &&
    typeof process.versions.node === 'string';
var require = achdIsNode ? (await import('node:module')).createRequire(import.meta.url) : undefined;
var __filename = achdIsNode ? require('node:url').fileURLToPath(import.meta.url) : undefined;
var __dirname = achdIsNode ? require('node:path').dirname(__filename) : undefined;
